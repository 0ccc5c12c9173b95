#pragma once
//! \file
//! Nearest-neighbour queries over a fixed set of points (a k-d tree, nanoflann inside).

#include "pdeface/core/mesh.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace pdeface {

//! A k-d tree over points that outlive it (the index keeps a view, not a copy). Queries are const and
//! safe from several threads at once.
class PointIndex {
public:
  //! \pre `points` stays alive and unchanged while the index is used.
  explicit PointIndex(std::span<const Vec3> points);
  ~PointIndex();
  PointIndex(PointIndex&&) noexcept;
  PointIndex& operator=(PointIndex&&) noexcept;

  struct Neighbour {
    std::size_t index;
    double distance; //!< Euclidean, not squared
  };

  //! The nearest point. \pre the index holds at least one point.
  [[nodiscard]] Neighbour nearest(const Vec3& query) const;
  //! The nearest point, searched from a guess (the index of a point believed near the query): the answer
  //! of `nearest` (but for a point exactly as near as the guess, which then wins), found sooner the
  //! nearer the guess. \pre `guess < size()`.
  [[nodiscard]] Neighbour nearest_from(const Vec3& query, std::size_t guess) const;
  //! The nearest point if one lies nearer than `bound`, else none: a far query ends early.
  [[nodiscard]] std::optional<Neighbour> nearest_within(const Vec3& query, double bound) const;
  //! The k nearest points, nearest first (fewer if the index holds fewer).
  [[nodiscard]] std::vector<Neighbour> nearest(const Vec3& query, std::size_t k) const;
  //! The same into `out` (replaced), whose memory a loop of queries re-uses: no allocation a query.
  void nearest(const Vec3& query, std::size_t k, std::vector<Neighbour>& out) const;
  //! Every point within `radius`, nearest first.
  [[nodiscard]] std::vector<Neighbour> within(const Vec3& query, double radius) const;
  //! The same points (nearer than `radius`), each given to `visit` with its squared distance as found,
  //! in no order and nothing held: for a query that keeps little of many points.
  void visit_within(const Vec3& query, double radius,
                    const std::function<void(std::size_t index, double squared)>& visit) const;

  [[nodiscard]] std::size_t size() const noexcept;

private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

} // namespace pdeface

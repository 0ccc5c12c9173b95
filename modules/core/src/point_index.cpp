#include "pdeface/core/point_index.hpp"

#include <array>

#include <nanoflann.hpp>

#include <cmath>
#include <limits>

namespace pdeface {

// nanoflann's dataset adaptor over a span of Eigen vectors.
struct PointIndex::Tree {
  struct Cloud {
    std::span<const Vec3> points;
    [[nodiscard]] std::size_t kdtree_get_point_count() const { return points.size(); }
    [[nodiscard]] double kdtree_get_pt(std::size_t i, std::size_t dim) const {
      return points[i][static_cast<Eigen::Index>(dim)];
    }
    template <class Box> bool kdtree_get_bbox(Box& /*unused*/) const { return false; }
  };
  using KdTree =
      nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3, std::size_t>;

  explicit Tree(std::span<const Vec3> points)
      : cloud{points}, index(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}

  Cloud cloud;
  KdTree index;
};

namespace {

// nanoflann's result-set interface for the one nearest point below a starting bound (squared): the same
// decisions as its `KNNResultSet` with k = 1, which starts from an infinite bound.
struct Closest {
  double worst;
  std::size_t index = std::numeric_limits<std::size_t>::max();
  // NOLINTNEXTLINE(readability-identifier-naming): nanoflann's names
  [[nodiscard]] double worstDist() const { return worst; }
  [[nodiscard]] bool full() const { return true; }
  // NOLINTNEXTLINE(readability-identifier-naming)
  bool addPoint(double squared, std::size_t i) {
    if (squared < worst) {
      worst = squared;
      index = i;
    }
    return true;
  }
};

// nanoflann's result-set interface for every point nearer than a radius, each handed on as found: the
// search passes on only points nearer than `worstDist()` (its `RadiusResultSet`'s test), so none is
// tested here again.
struct Visit {
  double radius_squared;
  const std::function<void(std::size_t, double)>* visit;
  // NOLINTNEXTLINE(readability-identifier-naming): nanoflann's names
  [[nodiscard]] double worstDist() const { return radius_squared; }
  [[nodiscard]] bool full() const { return true; }
  // NOLINTNEXTLINE(readability-identifier-naming)
  bool addPoint(double squared, std::size_t i) {
    (*visit)(i, squared);
    return true;
  }
};

} // namespace

PointIndex::PointIndex(std::span<const Vec3> points) : tree_(std::make_unique<Tree>(points)) {}
PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

std::size_t PointIndex::size() const noexcept { return tree_->cloud.points.size(); }

PointIndex::Neighbour PointIndex::nearest(const Vec3& query) const {
  std::size_t index = 0;
  double squared = 0.0;
  tree_->index.knnSearch(query.data(), 1, &index, &squared);
  return {index, std::sqrt(squared)};
}

PointIndex::Neighbour PointIndex::nearest_from(const Vec3& query, std::size_t guess) const {
  // The guess's squared distance as the tree measures it, so that the answer's distance is the same bits
  // whichever search found it.
  Closest closest{tree_->index.distance.evalMetric(query.data(), static_cast<unsigned>(guess), 3), guess};
  tree_->index.findNeighbors(closest, query.data(), nanoflann::SearchParams());
  return {closest.index, std::sqrt(closest.worst)};
}

std::optional<PointIndex::Neighbour> PointIndex::nearest_within(const Vec3& query, double bound) const {
  Closest closest{bound * bound};
  tree_->index.findNeighbors(closest, query.data(), nanoflann::SearchParams());
  if (closest.index == std::numeric_limits<std::size_t>::max()) return std::nullopt;
  return Neighbour{closest.index, std::sqrt(closest.worst)};
}

std::vector<PointIndex::Neighbour> PointIndex::nearest(const Vec3& query, std::size_t k) const {
  std::vector<Neighbour> out;
  nearest(query, k, out);
  return out;
}

void PointIndex::nearest(const Vec3& query, std::size_t k, std::vector<Neighbour>& out) const {
  k = std::min(k, size());
  // A few neighbours (the usual query) found into arrays on the stack, more into the heap.
  constexpr std::size_t kOnStack = 16;
  std::array<std::size_t, kOnStack> few_indices{};
  std::array<double, kOnStack> few_squared{};
  std::vector<std::size_t> many_indices;
  std::vector<double> many_squared;
  std::size_t* indices = few_indices.data();
  double* squared = few_squared.data();
  if (k > kOnStack) {
    many_indices.resize(k);
    many_squared.resize(k);
    indices = many_indices.data();
    squared = many_squared.data();
  }
  k = tree_->index.knnSearch(query.data(), k, indices, squared);
  out.resize(k);
  for (std::size_t i = 0; i < k; ++i)
    out[i] = {indices[i], std::sqrt(squared[i])};
}

std::vector<PointIndex::Neighbour> PointIndex::within(const Vec3& query, double radius) const {
  std::vector<std::pair<std::size_t, double>> matches;
  nanoflann::SearchParams params;
  params.sorted = true;
  tree_->index.radiusSearch(query.data(), radius * radius, matches, params);
  std::vector<Neighbour> out;
  out.reserve(matches.size());
  for (const auto& [index, squared] : matches)
    out.push_back({index, std::sqrt(squared)});
  return out;
}

void PointIndex::visit_within(const Vec3& query, double radius,
                              const std::function<void(std::size_t, double)>& visit) const {
  Visit set{radius * radius, &visit};
  tree_->index.findNeighbors(set, query.data(), nanoflann::SearchParams());
}

} // namespace pdeface

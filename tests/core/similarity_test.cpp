// The one similarity transform: apply and its inverse, composition, a change of scale, and the face frame
// built on it.

#include "pdeface/core/similarity.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace pdeface {
namespace {

Similarity turned() {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  return {r, Vec3(4, -5, 6), 25.4};
}

TEST(Similarity, AppliesScaleRotationThenTranslation) {
  const Similarity s = turned();
  const Vec3 p(1, 2, 3);
  EXPECT_EQ(s.apply(p), s.scale * (s.rotation * p) + s.translation); // the same bits, by definition
  EXPECT_TRUE(s.apply_inverse(s.apply(p)).isApprox(p, 1e-12));
  EXPECT_EQ(Similarity{}.apply(p), p);
}

TEST(Similarity, InverseUndoesIt) {
  const Similarity s = turned();
  const Similarity back = s.inverse();
  EXPECT_DOUBLE_EQ(back.scale, 1.0 / 25.4);
  EXPECT_TRUE((back.rotation * s.rotation).isIdentity(1e-12));
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(10, -3, 7), Vec3(-100, 50, 2)}) { // (isApprox is relative)
    EXPECT_LT((back.apply(s.apply(p)) - p).norm(), 1e-12 * (1.0 + p.norm())) << p.transpose();
    EXPECT_LT((back.apply(p) - s.apply_inverse(p)).norm(), 1e-12 * (1.0 + p.norm())) << p.transpose();
  }
}

TEST(Similarity, ComposesInOrder) {
  const Similarity first = turned();
  const Similarity second{Eigen::AngleAxisd(-1.1, Vec3::UnitY()).toRotationMatrix(), Vec3(0.5, 0, -2), 0.1};
  const Similarity both = second.after(first);
  for (const Vec3& p : {Vec3(1, 2, 3), Vec3(-4, 0, 9)})
    EXPECT_TRUE(both.apply(p).isApprox(second.apply(first.apply(p)), 1e-12)) << p.transpose();
  EXPECT_TRUE(first.inverse().after(first).apply(Vec3(3, 2, 1)).isApprox(Vec3(3, 2, 1), 1e-12));
}

TEST(Similarity, WithScaleKeepsTheRotationAndThePointAtTheOrigin) {
  const Similarity s = turned();
  const Similarity t = s.with_scale(1.0);
  EXPECT_EQ(t.scale, 1.0);
  EXPECT_EQ(t.rotation, s.rotation);
  const Vec3 origin = s.apply_inverse(Vec3::Zero()); // the source point at the origin stays there
  EXPECT_LT(t.apply(origin).norm(), 1e-12);
}

TEST(FaceFrame, IsASimilarityWithTheScansUnits) {
  FaceFrame f;
  static_cast<Similarity&>(f) = turned();
  f.scan_units = Units::Inches;
  const Vec3 p(1, 2, 3);
  EXPECT_EQ(f.to_canonical(p), f.apply(p));
  EXPECT_EQ(f.to_scan(p), f.apply_inverse(p));
  EXPECT_TRUE(f.origin_in_scan().isApprox(f.to_scan(Vec3::Zero())));
  EXPECT_EQ(f.axis_in_scan(1), f.rotation.row(1).transpose());
}

} // namespace
} // namespace pdeface

// face_errors (hrad compare's measure) against sums worked by hand, and its invariants: the
// groups' parts add in quadrature to the whole, the reference's noise is what it adds in
// expectation, and a reference that reflects nothing is refused.
#include "hrad/analysis/face_error.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "hrad/core/error.h"

namespace hrad {
namespace {

FaceValues face(double area, const Rgb& reflected, const Rgb& reference, const std::string& key,
                const Rgb& se = Rgb::Zero()) {
  return FaceValues{area, reflected, reference, se, key};
}

TEST(FaceError, TwoFacesByHand) {
  // Face 0 (area 2) reads 1.1 where the reference has 1 in every channel; face 1 (area 1) reads 0
  // where it has 0.5 in red only.
  const FaceErrors s = face_errors(
      {face(2.0, Rgb::Constant(1.1), Rgb::Constant(1.0), "a"), face(1.0, Rgb(0.0, 0.0, 0.0), Rgb(0.5, 0.0, 0.0), "b")});
  // numerator 2 * 3 * 0.01 + 0.25 = 0.31; denominator 2 * 3 + 0.25 = 6.25.
  EXPECT_NEAR(s.relative_l2, std::sqrt(0.31 / 6.25), 1e-15);
  // offsets 2 * 0.3 - 0.5 = 0.1 over 2 * 3 + 0.5 = 6.5.
  EXPECT_NEAR(s.bias, 0.1 / 6.5, 1e-15);
  EXPECT_EQ(s.largest_face, 1);  // 0.25 > 0.06
  EXPECT_NEAR(s.largest_face_share, 0.25 / 0.31, 1e-15);
  EXPECT_NEAR(s.largest_face_error, 1.0, 1e-15);
  ASSERT_EQ(s.face_error.size(), 2u);
  EXPECT_NEAR(s.face_error[0], 0.1, 1e-12);  // |0.1 (1,1,1)| / |(1,1,1)|
  EXPECT_NEAR(s.face_share[0], 0.06 / 0.31, 1e-15);
  EXPECT_NEAR(s.face_share[1], 0.25 / 0.31, 1e-15);
  ASSERT_EQ(s.groups.size(), 2u);
  EXPECT_EQ(s.groups[0].key, "b");
  EXPECT_NEAR(s.groups[0].bias, -1.0, 1e-15);
  EXPECT_NEAR(s.groups[1].bias, 0.1, 1e-15);
  EXPECT_NEAR(s.groups[1].l2_part, std::sqrt(0.06 / 6.25), 1e-15);
  EXPECT_EQ(s.reference_noise, 0.0);
  EXPECT_EQ(s.noise_corrected, s.relative_l2);
}

TEST(FaceError, GroupPartsAddInQuadratureAndSharesToOne) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<FaceValues> faces;
  for (int f = 0; f < 200; ++f)
    faces.push_back(
        face(0.1 + u(rng), Rgb(u(rng), u(rng), u(rng)), Rgb(u(rng), u(rng), u(rng)), "g" + std::to_string(f % 7)));
  const FaceErrors s = face_errors(faces);
  double parts2 = 0.0, shares = 0.0;
  for (const GroupError& g : s.groups) {
    parts2 += g.l2_part * g.l2_part;
    shares += g.error_share;
  }
  EXPECT_NEAR(std::sqrt(parts2), s.relative_l2, 1e-12);
  EXPECT_NEAR(shares, 1.0, 1e-12);
  for (std::size_t i = 1; i < s.groups.size(); ++i) EXPECT_GE(s.groups[i - 1].error_share, s.groups[i].error_share);
}

TEST(FaceError, ReferenceNoiseIsWhatItAddsInExpectation) {
  // An exact answer scored against a noisy reference (each face's value drawn about the truth with
  // the standard error it reports): relative_l2 is then the noise alone, which reference_noise
  // predicts, and the corrected figure is near 0.
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<FaceValues> faces;
  for (int f = 0; f < 20000; ++f) {
    const Rgb truth = Rgb(1.0, 0.8, 0.6), se = Rgb::Constant(0.05);
    faces.push_back(face(1.0, truth, truth + se * Rgb(n(rng), n(rng), n(rng)), "all", se));
  }
  const FaceErrors s = face_errors(faces);
  EXPECT_NEAR(s.relative_l2 / s.reference_noise, 1.0, 0.02);
  EXPECT_LT(s.noise_corrected, 0.25 * s.relative_l2);
}

TEST(FaceError, RefusesAReferenceThatReflectsNothing) {
  EXPECT_THROW(face_errors({}), Error);
  EXPECT_THROW(face_errors({face(1.0, Rgb::Constant(0.1), Rgb::Zero(), "a")}), Error);
}

}  // namespace
}  // namespace hrad

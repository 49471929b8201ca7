// The error of a solution's per-face reflected radiosity against a reference for the same faces:
// another solution, or the Monte Carlo ruler (lib/hrad/reference), whose values carry standard
// errors. This is how the per-polygon figures in the README are scored (`hrad compare`).
//
// Per input face f of area A_f, with d_f = (B_f - E_f) - (Bref_f - E_f) the difference of the
// reflected radiosities (emitters count by what they reflect, not by their given emission) and
// |.| the Euclidean norm over the three channels:
//   relative_l2     = sqrt( sum_f A_f |d_f|^2 / sum_f A_f |Bref_f - E_f|^2 )
//   reference_noise = sqrt( sum_f A_f |se_f|^2 / sum_f A_f |Bref_f - E_f|^2 ): what the reference's
//                     own standard errors se_f add to relative_l2 in expectation (in quadrature:
//                     E|d_f + noise|^2 = |d_f|^2 + |se_f|^2), 0 for a solution
//   noise_corrected = sqrt(max(0, relative_l2^2 - reference_noise^2))
//   bias            = sum_f A_f sum_c d_f[c] / sum_f A_f sum_c (Bref_f - E_f)[c] (the area mean's
//                     relative offset: its sign says too bright or too dark)
// Faces are grouped by a key (their material or group name); a group's `l2_part` is its faces'
// share of the numerator over the whole denominator, so the parts add in quadrature to relative_l2.
#pragma once

#include <string>
#include <vector>

#include "hrad/core/types.h"

namespace hrad {

struct FaceValues {
  double area = 0.0;
  Rgb reflected = Rgb::Zero();     ///< B - E
  Rgb reference = Rgb::Zero();     ///< Bref - E
  Rgb reference_se = Rgb::Zero();  ///< the reference's standard error per channel (0 if exact)
  std::string key;                 ///< grouping: material or group name
};

struct GroupError {
  std::string key;
  std::size_t faces = 0;
  double area = 0.0;
  double l2_part = 0.0;      ///< sqrt(sum over the group's faces of A |d|^2 / the whole denominator)
  double error_share = 0.0;  ///< the group's share of sum_f A_f |d_f|^2
  double bias = 0.0;         ///< as `bias`, over the group's faces (0/0 = 0)
};

struct FaceErrors {
  std::size_t faces = 0;
  double relative_l2 = 0.0;
  double reference_noise = 0.0;
  double noise_corrected = 0.0;
  double bias = 0.0;
  int largest_face = -1;            ///< the face with the largest A |d|^2
  double largest_face_share = 0.0;  ///< its share of sum_f A_f |d_f|^2
  double largest_face_error = 0.0;  ///< its own |d| / |Bref - E| (+inf when its reference is 0)
  std::vector<GroupError> groups;   ///< by decreasing error_share
  std::vector<double> face_error;   ///< per face: |d| / |Bref - E| (+inf when its reference is 0)
  std::vector<double> face_share;   ///< per face: its share of sum_f A_f |d_f|^2 (0 when that sum is 0)
};

/// Scores `faces` as above. Throws hrad::Error when there are no faces or the reference reflects
/// nothing (the relative error is then undefined).
FaceErrors face_errors(const std::vector<FaceValues>& faces);

}  // namespace hrad

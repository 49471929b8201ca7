// A sweep's reference as its final gather at the error samples, saved beside the sweep
// (reference_samples.json) and read back by a later sweep of the same scene (hrad sweep
// --reference-from DIR): the reference's solve and gather are most of a sweep's fixed cost (their
// seconds are in reference.json), and a sweep with other settings can reuse them.
//
// reference_samples.json: {"samples_per_patch": m, "layout": "jittered", "columns": ["patch", "x",
// "y", "z", "area", "r", "g", "b"], "samples": [[patch, x, y, z, area, r, g, b], ...]}, one row per
// sample of patch_samples(scene, m) in order, r g b the reflected radiosity B - E gathered there.
#pragma once

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "hrad/core/scene.h"
#include "hrad/experiments/sweep.h"

namespace hrad {

/// Writes the reference's gathered samples as described above, one sample per line
/// (reference.gathered must be filled).
void write_reference_samples(std::ostream& out, const Scene& scene, const Reference& reference, int samples_per_patch);

/// Reads `dir`/reference.json and `dir`/reference_samples.json written by an earlier sweep. The
/// samples must be patch_samples(scene, samples_per_patch) to 1e-9 of the scene's size (the same
/// scene, sample count and layout); otherwise, or on unreadable files, throws hrad::Error naming
/// the file and the first sample that differs. The Reference has `gathered` and `description`
/// (plus "reused_from": dir), and no solution: runs are judged at the samples only.
Reference read_reference_samples(const std::string& dir, const Scene& scene, int samples_per_patch);

}  // namespace hrad

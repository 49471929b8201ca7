// The solve report (`hrad solve --report R.json`): the interface other tools and checks read.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/reference/power_balance.h"
#include "hrad/solvers/solve.h"

namespace hrad {

/// The report of one solve:
///   scene, method, options {max_area, patch_area, feps, bfeps, aeps, source_levels, source_levels_near_lamps,
///   tolerance, max_iterations,
///     linear_solver, effects, kernel, visibility_samples, clustering, push, basis, balance, threads}: as the solve
///     used them (SolveSummary::used: automatic values filled in, the method's kernel),
///   termination ("converged" | "max_iterations" | "direct" | "failed"), status (the same), message,
///   iterations, elements, links, patch_count (Scene::patches), form_factor_evaluations, visibility_queries,
///   work {gather_terms, point_factor_evaluations, form_factor_evaluations, segment_queries,
///     shaft_queries, link_bytes, candidate_pairs} (work.h: what the solve did, counted where done),
///   seconds {total, <phase>: s, ...}, effects {visibility, color_channels, bounces, cull_facing_away, reasons},
///   change_per_iteration [..], peak_memory_bytes, figures {name: value},
///   energy {emitted_power, radiosity_power}: sums of area * E and area * B over the elements (channel means),
///   power_balance (power_balance_json(); written by `hrad solve`, which also prints it, and adds
///     options.cut_near_faces: whether the reader cut faces along near faces, io/near_faces.h),
///   patches: one entry per input face (Scene::faces) in file order:
///     {face, line, group, material, area, emission [r,g,b], reflectance [r,g,b], radiosity [r,g,b]}
///     where radiosity is the area average over the face's patches.
nlohmann::json solve_report_json(const Scene& scene, const SolveOptions& options, const SolveSummary& summary,
                                 const Solution& solution);

/// The power balance (reference/power_balance.h) as the report's `power_balance` entry:
///   {emitted, absorbed_reflecting, absorbed_black, onto_backs, escaped, sampled_se, residual}: channel
///   means in power units; relative_residual, allowed (shares of the emitted power), balanced, rays.
nlohmann::json power_balance_json(const PowerBalance& balance);

/// Writes `report` (indented) to `path` atomically; hrad::Error naming `path` on failure.
void write_json_file(const std::string& path, const nlohmann::json& report);

}  // namespace hrad

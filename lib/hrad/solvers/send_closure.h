// Closure of what elements send: the parts of an element split below --aeps (--source-levels), and
// linear leaves. An element at aeps splits for the links that asked for its parts (a source whose
// radiosity varies where a receiver's kernel peaks); its other links stay at the element, or
// above, and reach its parts through their fields over it (push_pull.h), fitted to nine points of
// a larger element. Those fields do not vary as the parts' own links do: a part whose own link
// takes much of its hemisphere (beside a contact, a millimetre from a lamp) still sends by the full
// fields of the others, and the brighter the part the more it sends in all. The closure errors,
// summed against the parts' radiosities, made light: the generated warehouse (hrad scene generate
// --kind shelves) with `--source-levels auto` gained 2.2e-3 of its emitted power, parts sending up
// to 16% more than their radiosity.
//
// In a closed room every point's closure is 1, and the mean over an element at aeps of what its
// parts send per unit radiosity is right (each link's mean factor is; the fields only spread it).
// So each part L of such an element sends, through the links between elements, sigma_bar times
// its power, where sigma_L is what a unit radiosity on L sends through them (the adjoint of the
// gather, HsaLinks::send_coefficients(), carried down by the push's restriction) and sigma_bar its
// area mean over the element: a row-sum closure, as view-factor matrices are closed (van Leersum
// 1989, viewfactors/closure.h), per part. The part's moments move along a uniform field's by what
// it sends too much (PushPull::set_send_closure()): a constant part's are scaled by sigma_bar /
// sigma_L; a linear part keeps its slope, so that each link still weighs its radiosity by its
// field, and sends its power as closed (its slope against the same fields made light too: the lamp
// 1 mm from its wall, notebooks_data/scenes/lamp_near_wall.obj, gained 1.6e-3 with --basis linear;
// sending the parts' means instead balanced it but took RenderPark's office2 from 0.81% to 1.48%
// against the ruler, where this gives 0.72%). Where light leaves the element (its links take less
// than kClosedBlock of its hemisphere) its parts' closures differ by what each sees of the opening,
// and they send as before. Receiving is unchanged.
//
// A link with a cluster end reads the mean radiosity of the element it joins (hsa_links.h), so
// each leaf below that element sends the same share through it per unit area, while what each
// leaf's hemisphere gives the cluster varies: the foot of a wall tile, behind blocks low over the
// floor, sees less of the far room than its top. The element links, resolved per leaf, then close
// the leaves unevenly (the quarters of a 1 m tile in a room of boxes: 1.04 at the foot, 0.96
// above; 0.93 to 1.07 in rooms of floating blocks), and where the darker leaves send more the room
// loses power: 1.6e-3 to 3.6e-3 of it in rooms of 1 m tiles with a grid of boxes, up to 1e-3 in
// the generated 600-polygon offices (hrad scene generate --polygons 600 --seed 1..6). In a closed
// room every leaf's closure is 1 and its patch's mean over the leaves is right (the links' factors
// are means over the elements they join). So with constant leaves and the HSA push, each leaf of a
// split patch that cluster links reach and whose links take at least kClosedBlock of its
// hemisphere sends, through the element links, what brings its whole closure to the mean of those
// leaves of its patch: a quarter of the rooms' losses is left or less, the offices balance within
// 6e-4. Where light leaves (a leaf below kClosedBlock) it sends as before; a solve without clusters
// has none of this (the Cornell box is unchanged).
//
// A linear leaf at or above aeps has the same round trip within itself: what it receives through a
// link follows the link's field over it, its slope follows, and it sends by the same field, so an
// error of the field is squared into light (the lamp 1 mm from its wall gained 7.2e-4 of its power
// with --basis linear, the generated warehouse 8e-4). Where its links take at least kClosedBlock of
// its hemisphere, so that its closure is 1 at every point, it sends its power times sigma_L, what a
// uniform radiosity on it sends: the slope shares that among the links but adds none (1e-5 and
// 2e-6 of the power then). Where light leaves it the closure varies over it (a wall's foot sees
// the ground, its top the sky) and its slope sends as it says.
#pragma once

#include <vector>

#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/hsa_links.h"
#include "hrad/solvers/push_pull.h"

namespace hrad {

/// The parts of an element at aeps are closed when its links take at least this share of its
/// hemisphere (the area mean of what a unit radiosity on it sends through all of them): in a
/// closed room every part's closure is 1 (the generated rooms' elements at aeps: 0.95 to 1.05,
/// sampled cluster links included), where light escapes it may vary over the element (the
/// generated city's, open at the sides: 0.4 to 0.7; closed to their means, its parts at the
/// buildings' feet sent too little and the error per polygon went up from 2.2% to 2.9%).
inline constexpr double kClosedBlock = 0.9;
/// A leaf under cluster links, or any leaf of a scene that keeps its light, is closed only where
/// that moves what it sends through the element links by at most this share.
inline constexpr double kLargestClosureMove = 0.25;

/// Per element (node id), what PushPull::set_send_closure() takes: on the leaves below the
/// elements that cannot split (area / 4 < `aeps`), their coefficients, sigma_L and sigma_bar; with
/// `linear`, on the other leaves whose links close them, sigma_L as what they should send; with
/// `under_clusters` (constant leaves), on the other leaves of a split patch that cluster links
/// reach and whose links close them, what brings their whole closure to their patch's mean; `closed`
/// 0 elsewhere. With `closed_scene` (the scene keeps its light, closed_scene.h), every leaf that
/// sends through element links instead sends through them what brings its whole closure to 1,
/// wherever that moves them by at most kLargestClosureMove (the rules above elsewhere), and
/// `*unclosed` (when not null) counts the leaves it could not close so. Empty when there is nothing
/// to close.
std::vector<SendClosure> send_closures(const ElementHierarchy& hierarchy, const HsaLinks& links,
                                       const PushPull& push_pull, double aeps, bool linear, bool under_clusters = false,
                                       bool closed_scene = false, std::size_t* unclosed = nullptr);

}  // namespace hrad

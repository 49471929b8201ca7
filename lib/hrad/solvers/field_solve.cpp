#include "hrad/solvers/field_solve.h"

#include "hrad/solvers/iteration.h"
#include "hrad/solvers/push_pull.h"

namespace hrad {

SolveSummary solve_linear_field(SolverContext& ctx, ElementHierarchy& h, const FieldLinks& links, std::size_t factors,
                                Solution* out) {
  ctx.summary().work.gather_terms = links.terms();
  ctx.summary().work.link_bytes = links.bytes();
  const PushPull push_pull(ctx.scene(), h, nullptr, ctx.channels(), Basis::kLinear);
  NodeField field = push_pull.make_field();
  {
    auto phase = ctx.phase("solve");
    const LinkOperator* ops[] = {&links};
    iterate(ctx, push_pull, ops, field, radiosity_bound(ctx.scene()));
    push_pull.store(field, h, nullptr);
  }
  if (ctx.channels() == 1) {
    for (std::size_t i = 0; i < h.size(); ++i) copy_gray(h.node(static_cast<NodeId>(i)).radiosity), copy_gray(h.node(static_cast<NodeId>(i)).gathered);
    for (PointValues& v : field.point_radiosity)
      for (Rgb& b : v) copy_gray(b);
  }
  return ctx.finish(h, factors, out, field.point_radiosity);
}

}  // namespace hrad

#include "hrad/solvers/dense_links.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace hrad {

DenseLinks::DenseLinks(std::vector<NodeId> receivers, std::vector<NodeId> sources)
    : receivers_(std::move(receivers)),
      sources_(std::move(sources)),
      storage_(receivers_.size() * sources_.size(), 0.0) {}

void DenseLinks::gather(NodeField& field) const {
  const Eigen::Map<const RowMatrix> f = matrix();
  tbb::parallel_for(
      tbb::blocked_range<Eigen::Index>(0, rows(), 16), [&](const tbb::blocked_range<Eigen::Index>& range) {
        for (Eigen::Index i = range.begin(); i != range.end(); ++i) {
          Rgb sum = Rgb::Zero();
          for (Eigen::Index j = 0; j < cols(); ++j)
            sum += f(i, j) * field.radiosity[static_cast<std::size_t>(sources_[static_cast<std::size_t>(j)])];
          add_constant(field.irradiance[static_cast<std::size_t>(receivers_[static_cast<std::size_t>(i)])], sum);
        }
      });
}

}  // namespace hrad

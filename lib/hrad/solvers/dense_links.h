// A dense matrix of factors between a list of receiving nodes and a list of sending nodes: the
// full matrix's n x n F (elements to elements) and substructuring's n x N (elements to shooting
// patches, whose radiosity push_pull.h pulls as the area mean of their elements).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "hrad/core/huge_page_allocator.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/link_operator.h"

namespace hrad {

class DenseLinks final : public LinkOperator {
 public:
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  /// F(receivers[i] -> sources[j]) in row i, column j, zero until filled through matrix().
  /// Huge pages (BigVector): zero-filling GBs of 4 kB pages is slow (huge_page_allocator.h).
  DenseLinks(std::vector<NodeId> receivers, std::vector<NodeId> sources);

  Eigen::Map<RowMatrix> matrix() { return {storage_.data(), rows(), cols()}; }
  Eigen::Map<const RowMatrix> matrix() const { return {storage_.data(), rows(), cols()}; }
  Eigen::Index rows() const { return static_cast<Eigen::Index>(receivers_.size()); }
  Eigen::Index cols() const { return static_cast<Eigen::Index>(sources_.size()); }
  const std::vector<NodeId>& receivers() const { return receivers_; }
  const std::vector<NodeId>& sources() const { return sources_; }

  void gather(NodeField& field) const override;
  std::uint64_t terms() const override { return receivers_.size() * sources_.size(); }
  std::uint64_t bytes() const override { return terms() * sizeof(double); }

 private:
  std::vector<NodeId> receivers_, sources_;
  BigVector<double> storage_;
};

}  // namespace hrad

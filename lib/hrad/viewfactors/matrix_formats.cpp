#include "hrad/viewfactors/matrix_formats.h"

#include <filesystem>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "hrad/core/error.h"

namespace hrad {

MatrixFormat matrix_format(const std::string& name, const std::string& path, const std::string& option) {
  if (name == "dense") return MatrixFormat::kDense;
  if (name == "triplets") return MatrixFormat::kTriplets;
  if (name == "mtx") return MatrixFormat::kMatrixMarket;
  if (name == "view3d") return MatrixFormat::kView3d;
  if (!name.empty()) throw Error(fmt::format("--format: '{}' is not one of dense, triplets, mtx, view3d", name));
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".csv") return MatrixFormat::kDense;
  if (ext == ".mtx") return MatrixFormat::kMatrixMarket;
  if (ext == ".txt") return MatrixFormat::kView3d;
  throw Error(fmt::format("{} {}: unknown extension '{}' (.csv, .mtx or .txt; or give --format)", option, path, ext));
}

void write_matrix(std::ostream& out, const ViewFactorMatrix& m, const SurfaceUnits& units, MatrixFormat format) {
  std::string line;
  auto dense_row = [&](int u, const char* separator) {
    line.clear();
    std::int64_t k = m.row_begin[static_cast<std::size_t>(u)];
    const std::int64_t end = m.row_begin[static_cast<std::size_t>(u) + 1];
    for (int v = 0; v < m.n; ++v) {
      if (v > 0) line += separator;
      if (k < end && m.column[static_cast<std::size_t>(k)] == v)
        fmt::format_to(std::back_inserter(line), "{:.17g}", m.factor(u, k++));
      else
        line += '0';
    }
    line += '\n';
    out << line;
  };
  switch (format) {
    case MatrixFormat::kDense:
      for (int u = 0; u < m.n; ++u) dense_row(u, ",");
      break;
    case MatrixFormat::kTriplets:
    case MatrixFormat::kMatrixMarket: {
      const bool mm = format == MatrixFormat::kMatrixMarket;
      if (mm) {
        out << "%%MatrixMarket matrix coordinate real general\n";
        out << "% view factors F(i -> j) written by hrad viewfactors; rows and columns are surfaces in order\n";
        out << fmt::format("{} {} {}\n", m.n, m.n, m.nonzeros());
      } else {
        out << "i,j,F\n";
      }
      for (int u = 0; u < m.n; ++u)
        for (std::int64_t k = m.row_begin[static_cast<std::size_t>(u)];
             k < m.row_begin[static_cast<std::size_t>(u) + 1]; ++k) {
          const int v = m.column[static_cast<std::size_t>(k)];
          out << (mm ? fmt::format("{} {} {:.17g}\n", u + 1, v + 1, m.factor(u, k))
                     : fmt::format("{},{},{:.17g}\n", u, v, m.factor(u, k)));
        }
      break;
    }
    case MatrixFormat::kView3d: {
      // View3D 3.x writes "version format enclosure emissivities surfaces" on the first line; its
      // readers skip that line and read the numbers after it.
      out << fmt::format("View3D 3.2 0 0 1 {}\n", m.n);
      line.clear();
      for (int u = 0; u < m.n; ++u)
        fmt::format_to(std::back_inserter(line), "{}{:.17g}", u ? " " : "", m.area[static_cast<std::size_t>(u)]);
      out << line << '\n';
      for (int u = 0; u < m.n; ++u) dense_row(u, " ");
      line.clear();
      for (int u = 0; u < m.n; ++u)
        fmt::format_to(std::back_inserter(line), "{}{:.17g}", u ? " " : "",
                       units.emissivity[static_cast<std::size_t>(u)]);
      out << line << '\n';
      break;
    }
  }
}

}  // namespace hrad

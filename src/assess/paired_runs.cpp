#include "assess/paired_runs.hpp"

#include <algorithm>
#include <vector>

#include "assess/cluster.hpp"
#include "invariant/check.hpp"

namespace j232::assess {

PairedSums run_paired(const PairedRuns& p) {
  J232_CHECK(p.designs >= 1 && p.block >= 1 && p.segment >= 1 && p.segment % p.block == 0);
  PairedSums total(p.designs, p.figures);
  const bool writer = cluster::is_writer();
  std::vector<std::vector<double>> own(p.designs);  // a segment's figures: [design][unit in segment * figures + figure]
  for (std::uint64_t first = 0; first < p.units; first += p.segment) {
    const std::uint64_t count = std::min(p.segment, p.units - first);
    for (std::size_t d = 0; d < p.designs; ++d) {
      own[d].assign(writer ? static_cast<std::size_t>(count) * p.figures : 0, 0.0);
      p.run(d, first, count, [&, d](std::uint64_t unit, const double* figures) {
        J232_CHECK(unit >= first && unit < first + count);
        std::copy(figures, figures + p.figures, own[d].begin() + static_cast<std::ptrdiff_t>((unit - first) * p.figures));
      });
    }
    if (!writer) continue;
    const auto at = [&](std::uint64_t unit, std::size_t j) { return static_cast<std::size_t>(unit - first) * p.figures + j; };
    total.add_units(
        first, count, p.block,
        [&](std::uint64_t unit, double* y) {
          for (std::size_t d = 0; d < p.designs; ++d)
            for (std::size_t j = 0; j < p.figures; ++j) {
              const double figure = own[d][at(unit, j)];
              y[d * p.figures + j] = p.value ? p.value(d, unit, j, figure) : figure;
            }
        },
        [&](std::uint64_t unit, std::size_t d, std::size_t j) { return own[d][at(unit, j)] != own[0][at(unit, j)]; });
  }
  return total;
}

}  // namespace j232::assess

#pragma once
// The sums every paired comparison of designs rests on: the same
// units (a J232 test's replicates, a field's objects) run on each design with common random
// numbers, each unit giving every design a value of each figure. Kept per design and figure:
// the values' sum and sum of squares (each design's own estimate and spread) and, for every
// design after the first, the sum and sum of squares of its differences from the first and
// the units whose own figure differs from the first's (the paired estimate, its spread, and
// what a run with none differing could have missed). Units are added in their order and
// chunks merged in chunk order, so the sums are the same on any thread or rank count. Both
// comparisons (assess::run_paired for study::compare_designs and field::compare_fields;
// study::compare_records for a batch's designs run apart; docs/model.md §6a and §9.2) add to
// this one type; each turns the sums into its own intervals.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "assess/bytes.hpp"
#include "invariant/check.hpp"

namespace j232::assess {

struct PairedSums {
  std::size_t designs = 0, figures = 0;
  std::uint64_t units = 0;
  std::vector<double> sum, squares;                 // [design * figures + figure]
  std::vector<double> diff, diff_squares;           // [(design - 1) * figures + figure]: design minus the first
  std::vector<std::uint64_t> differing;             // [(design - 1) * figures + figure]: units whose own figure differs
  std::vector<std::uint64_t> units_differing;       // [design - 1]: units in which any figure differs

  PairedSums() = default;
  PairedSums(std::size_t designs_, std::size_t figures_) { zero(designs_, figures_); }

  // Every sum zero, for `designs_` designs (at least one) of `figures_` figures each.
  void zero(std::size_t designs_, std::size_t figures_) {
    J232_CHECK(designs_ >= 1);
    designs = designs_, figures = figures_, units = 0;
    sum.assign(designs * figures, 0.0), squares.assign(designs * figures, 0.0);
    diff.assign((designs - 1) * figures, 0.0), diff_squares.assign((designs - 1) * figures, 0.0);
    differing.assign((designs - 1) * figures, 0), units_differing.assign(designs - 1, 0);
  }

  // One unit's values, y[design * figures + figure]. `differs(design, figure)`: whether the
  // unit's own figure in `design` differs from the first design's (a field's object: its
  // counts, not its values, which carry each design's weight per object).
  template <class Differs>
  void add(const double* y, Differs&& differs) {
    ++units;
    for (std::size_t i = 0; i < designs * figures; ++i) sum[i] += y[i], squares[i] += y[i] * y[i];
    for (std::size_t d = 1; d < designs; ++d) {
      bool any = false;
      for (std::size_t j = 0; j < figures; ++j) {
        const std::size_t at = (d - 1) * figures + j;
        const double delta = y[d * figures + j] - y[j];
        diff[at] += delta, diff_squares[at] += delta * delta;
        const bool other = differs(d, j);
        differing[at] += other ? 1 : 0;
        any = any || other;
      }
      units_differing[d - 1] += any ? 1 : 0;
    }
  }
  // (A unit's figures differ where their values do.)
  void add(const double* y) {
    add(y, [&](std::size_t d, std::size_t j) { return y[d * figures + j] != y[j]; });
  }

  // Another chunk's sums added after these (chunks merged in chunk order).
  void merge(const PairedSums& o) {
    J232_CHECK(o.designs == designs && o.figures == figures);
    units += o.units;
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += o.sum[i], squares[i] += o.squares[i];
    for (std::size_t i = 0; i < diff.size(); ++i)
      diff[i] += o.diff[i], diff_squares[i] += o.diff_squares[i], differing[i] += o.differing[i];
    for (std::size_t i = 0; i < units_differing.size(); ++i) units_differing[i] += o.units_differing[i];
  }

  // As bytes between MPI ranks, and back (the shape, designs and figures, is the reader's).
  void pack(ByteWriter& w) const {
    w.value(units);
    for (const auto* v : {&sum, &squares, &diff, &diff_squares}) w.list(*v, v->size());
    w.list(differing, differing.size()), w.list(units_differing, units_differing.size());
  }
  void unpack(ByteReader& r) {
    units = r.value<std::uint64_t>();
    for (auto* v : {&sum, &squares, &diff, &diff_squares}) r.list(*v);
    r.list(differing), r.list(units_differing);
    const std::size_t own_size = designs * figures, versus_size = (designs - 1) * figures;
    if (sum.size() != own_size || squares.size() != own_size || diff.size() != versus_size || diff_squares.size() != versus_size ||
        differing.size() != versus_size || units_differing.size() != designs - 1)
      throw std::runtime_error("a message between ranks held paired sums of another shape");
  }

  // Units [first, first + count) after those added so far, each filled by `fill(unit, y)`
  // (y[design * figures + figure]) and judged by `differs(unit, design, figure)` (after its
  // fill): added in unit order into blocks of `block` units (unit u in block u / block; `first`
  // a block's first unit) whose sums are merged into these in order. The one way both
  // comparisons add their units (a J232 comparison's replicates in one block; a field's objects
  // in blocks of its runner's chunk, which holds a long run's rounding down), and the same
  // sums however the units are handed over (all at once, or a field's in segments).
  template <class Fill, class Differs>
  void add_units(std::uint64_t first, std::uint64_t count, std::uint64_t block, Fill&& fill, Differs&& differs) {
    J232_CHECK(block >= 1 && first % block == 0);
    PairedSums part(designs, figures);
    std::vector<double> y(designs * figures);
    for (std::uint64_t start = first; start < first + count; start += block) {
      part.zero(designs, figures);
      for (std::uint64_t i = start; i < first + count && i < start + block; ++i) {
        fill(i, y.data());
        part.add(y.data(), [&](std::size_t d, std::size_t j) { return differs(i, d, j); });
      }
      merge(part);
    }
  }

  // Indexing: design d's figure j, and design d's (d >= 1) difference from the first.
  std::size_t own(std::size_t d, std::size_t j) const { return d * figures + j; }
  std::size_t versus_first(std::size_t d, std::size_t j) const {
    J232_CHECK(d >= 1 && d < designs);
    return (d - 1) * figures + j;
  }
};

}  // namespace j232::assess

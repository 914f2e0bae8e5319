#pragma once
// The one paired comparison of designs (docs/model.md §6a, §9.2): the same units (a J232
// test's replicates, a field's objects) run on every design with common random numbers, on
// the one runner, each unit's own figures handed over in unit order, and added in unit order
// into assess::PairedSums. Both comparisons (study::compare_designs, field::compare_fields)
// are this driver with their pipeline's run of a design and, for a field, the weight each
// object's counts carry; each turns the sums into its own intervals.
#include <cstddef>
#include <cstdint>
#include <functional>

#include "assess/paired_sums.hpp"

namespace j232::assess {

// Receives one unit's own figures (`figures` of them), in unit order.
using UnitSink = std::function<void(std::uint64_t unit, const double* figures)>;

struct PairedRuns {
  std::size_t designs = 0, figures = 0;
  std::uint64_t units = 0;
  // Units are added in blocks of `block` units whose sums are merged in order
  // (PairedSums::add_units), and run a segment of `segment` units at a time, every design in
  // turn over it, so that only a segment's figures are held; both are whole multiples of the
  // pipeline's runner's chunk. The sums do not depend on `segment`.
  std::uint64_t block = 1, segment = 1;
  // Runs design d's units [first, first + count) (after its units before `first`), handing each
  // unit's figures to `sink` in unit order (on rank 0 of an MPI job; on the others, never).
  std::function<void(std::size_t d, std::uint64_t first, std::uint64_t count, const UnitSink& sink)> run;
  // A unit's value of figure j in design d from its own figure (a field's object's count
  // carries its design's weight per object); the figure itself when not given. A unit's figure
  // differs from the first design's where its own figure does, whatever the weights.
  std::function<double(std::size_t d, std::uint64_t unit, std::size_t j, double own)> value;
};

// Every design's units, paired. In an MPI job rank 0's sums are the run's; the other ranks'
// hold no unit.
PairedSums run_paired(const PairedRuns& p);

}  // namespace j232::assess

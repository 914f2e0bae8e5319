#pragma once
// Counts heap allocations made on the calling thread between start() and stop(), via
// replaced global operator new (allocation_counter.cpp) — to show that the per-nail
// path allocates nothing.
namespace j232::test::allocations {
void start();
long stop();  // allocations since start()
}  // namespace j232::test::allocations

#pragma once
// The processes of an MPI job (docs/model.md §5.7, "Beyond one machine"): under `mpirun -n N`
// every rank runs the same command on the same inputs, each with its own threads; the
// runner shares each assessment's waves of replicate chunks out among the ranks and rank 0
// merges every chunk in index order, then hands the merged assessment back to all ranks,
// so each rank follows the same path and the result is bit-identical to one process. Only
// rank 0 writes files and prints. Built without MPI, or started without mpirun, there is
// one rank and nothing here does anything.
#include <string>

namespace j232::assess::cluster {

// Joins the MPI job when the process was started by an MPI launcher (it leaves MPI alone
// otherwise, so a plain `j232 run` never pays for it). Call once, first thing in main.
void init(int* argc, char*** argv);
// Leaves the job (normal exit).
void finalize();
// Ends the whole job at once with `code` (an error on any rank: no rank waits for ever and
// no partial result is written).
[[noreturn]] void abort(int code);

int rank();
int size();
inline bool is_writer() { return rank() == 0; }
// Whether this build can join MPI jobs.
bool available();

// Point to point and broadcast of opaque bytes (a serialised chunk or assessment).
void send(int to, const std::string& bytes);
std::string receive(int from);
void broadcast_from_writer(std::string& bytes);

}  // namespace j232::assess::cluster

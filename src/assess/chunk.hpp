#pragma once
// What one chunk of replicates produced, before it is merged (assess/runner.cpp), and its
// form on the wire between the ranks of an MPI job (assess/cluster.hpp).
#include <string>
#include <vector>

#include "assess/runner.hpp"

namespace j232::assess {

struct ChunkResult : NailRecords {
  std::vector<ReplicateTally> tallies;
  std::vector<MarkRow> marks;

  void clear() { *this = ChunkResult(); }
};

// Bytes for the ranks of one job (the same program on the same machine kind): the chunks
// of a wave, and a merged assessment (its results, not its provenance or paths).
std::string pack_chunks(const std::vector<ChunkResult>& chunks, std::size_t count);
void unpack_chunks(const std::string& bytes, std::vector<ChunkResult>& slots, std::size_t count);  // into slots [0, count)
std::string pack_assessment(const Assessment& a);
void unpack_assessment(const std::string& bytes, Assessment& a);

}  // namespace j232::assess

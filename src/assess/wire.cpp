// The bytes of chunks and assessments passed between the ranks of an MPI job. Every rank
// runs the same executable, so values go as their object representation; MarkRow holds only
// numbers and enums (Eigen's fixed-size vectors are plain arrays of doubles).
#include <stdexcept>

#include "assess/bytes.hpp"
#include "assess/chunk.hpp"

namespace j232::assess {

namespace {
void put(ByteWriter& w, const Histogram& h) {
  w.value(h.bin_width), w.value(h.origin), w.list(h.counts, h.counts.size()), w.value(h.total), w.value(h.sum);
}
void get(ByteReader& r, Histogram& h) {
  h.bin_width = r.value<double>(), h.origin = r.value<double>(), r.list(h.counts), h.total = r.value<std::uint64_t>(),
  h.sum = r.value<double>();
}
void put(ByteWriter& w, const Largest& l) { w.value(l.value); }
void get(ByteReader& r, Largest& l) { l.value = r.value<std::uint64_t>(); }
void put(ByteWriter& w, const ExitTable& e) {
  w.map(e.nails), w.map(e.marks), w.value(e.marks_by_strikes), w.value(e.marks_by_first_touch);
}
void get(ByteReader& r, ExitTable& e) {
  r.map(e.nails), r.map(e.marks);
  e.marks_by_strikes = r.value<decltype(e.marks_by_strikes)>();
  e.marks_by_first_touch = r.value<decltype(e.marks_by_first_touch)>();
}
void put(ByteWriter& w, const StationOutcomes& o) {
  w.value<std::uint64_t>(o.by_station.size());
  for (const auto& station : o.by_station) w.map(station);
}
void get(ByteReader& r, StationOutcomes& o) {
  o.by_station.resize(r.value<std::uint64_t>());
  for (auto& station : o.by_station) r.map(station);
}
void put(ByteWriter& w, std::uint64_t count) { w.value(count); }
void get(ByteReader& r, std::uint64_t& count) { count = r.value<std::uint64_t>(); }
// Every record of a nail (NailRecords::zip: the list merge uses too).
void put(ByteWriter& w, const NailRecords& n) {
  NailRecords::zip(n, n, [&](const auto& record, const auto&) { put(w, record); });
}
void get(ByteReader& r, NailRecords& n) {
  NailRecords::zip(n, n, [&](auto& record, auto&) { get(r, record); });
}
}  // namespace

std::string pack_chunks(const std::vector<ChunkResult>& chunks, std::size_t count) {
  ByteWriter w;
  w.value<std::uint64_t>(count);
  for (std::size_t i = 0; i < count; ++i) {
    const ChunkResult& c = chunks[i];
    put(w, c);
    w.list(c.tallies, c.tallies.size()), w.list(c.marks, c.marks.size());
  }
  return w.take();
}

void unpack_chunks(const std::string& bytes, std::vector<ChunkResult>& slots, std::size_t count) {
  ByteReader r(bytes);
  if (r.value<std::uint64_t>() != count || slots.size() < count) throw std::runtime_error("a message between ranks holds another number of chunks than its wave");
  for (std::size_t i = 0; i < count; ++i) {
    ChunkResult& c = slots[i];
    c.clear();
    get(r, c);
    r.list(c.tallies), r.list(c.marks);
  }
  if (!r.done()) throw std::runtime_error("a message between ranks was longer than its contents");
}

std::string pack_assessment(const Assessment& a) {
  ByteWriter w;
  put(w, a);
  w.value(a.replicates), w.value(a.passed), w.value(a.criterion_passed);
  for (const auto& s : a.shares) w.map(s.counts), w.value(s.total), w.value(s.sum);
  w.value(a.marks), w.value(a.uncounted_marks), w.value(a.fates);
  w.list(a.mark_sample, a.mark_sample.size()), w.value(a.mark_sample_replicates), w.value(a.mark_sample_closed);
  return w.take();
}

void unpack_assessment(const std::string& bytes, Assessment& a) {
  ByteReader r(bytes);
  get(r, a);
  a.replicates = r.value<std::uint64_t>(), a.passed = r.value<std::uint64_t>();
  a.criterion_passed = r.value<decltype(a.criterion_passed)>();
  for (auto& s : a.shares) r.map(s.counts), s.total = r.value<std::uint64_t>(), s.sum = r.value<double>();
  a.marks = r.value<std::uint64_t>(), a.uncounted_marks = r.value<std::uint64_t>();
  a.fates = r.value<decltype(a.fates)>();
  r.list(a.mark_sample);
  a.mark_sample_replicates = r.value<std::uint64_t>(), a.mark_sample_closed = r.value<bool>();
  if (!r.done()) throw std::runtime_error("a message between ranks was longer than its contents");
}

}  // namespace j232::assess

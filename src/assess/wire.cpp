// The bytes of chunks and assessments passed between the ranks of an MPI job. Every rank
// runs the same executable, so values go as their object representation; MarkRow holds only
// numbers and enums (Eigen's fixed-size vectors are plain arrays of doubles).
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "assess/chunk.hpp"

namespace j232::assess {

namespace {
class Writer {
 public:
  template <class T>
  void raw(const T& v) {
    const auto* p = reinterpret_cast<const char*>(&v);
    out_.append(p, sizeof(T));
  }
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    raw(v);
  }
  template <class T>
  void list(const std::vector<T>& v, std::size_t n) {
    value<std::uint64_t>(n);
    for (std::size_t i = 0; i < n; ++i) raw(v[i]);
  }
  template <class K, class V>
  void map(const std::map<K, V>& m) {
    value<std::uint64_t>(m.size());
    for (const auto& [k, v] : m) value(k), value(v);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  void raw(T& v) {
    if (at_ + sizeof(T) > bytes_.size()) throw std::runtime_error("a message between ranks ended early");
    std::memcpy(reinterpret_cast<char*>(&v), bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
  }
  template <class T>
  T value() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    raw(v);
    return v;
  }
  template <class T>
  void list(std::vector<T>& v) {
    const auto n = value<std::uint64_t>();
    v.resize(n);
    for (auto& x : v) raw(x);
  }
  template <class K, class V>
  void map(std::map<K, V>& m) {
    m.clear();
    for (auto n = value<std::uint64_t>(); n > 0; --n) {
      const K k = value<K>();
      m[k] = value<V>();
    }
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  const std::string& bytes_;
  std::size_t at_ = 0;
};

void put(Writer& w, const Histogram& h) {
  w.value(h.bin_width), w.value(h.origin), w.list(h.counts, h.counts.size()), w.value(h.total), w.value(h.sum);
}
void get(Reader& r, Histogram& h) {
  h.bin_width = r.value<double>(), h.origin = r.value<double>(), r.list(h.counts), h.total = r.value<std::uint64_t>(),
  h.sum = r.value<double>();
}
void put(Writer& w, const ExitTable& e) {
  w.map(e.nails), w.map(e.marks), w.value(e.marks_by_strikes), w.value(e.marks_by_first_touch);
}
void get(Reader& r, ExitTable& e) {
  r.map(e.nails), r.map(e.marks);
  e.marks_by_strikes = r.value<decltype(e.marks_by_strikes)>();
  e.marks_by_first_touch = r.value<decltype(e.marks_by_first_touch)>();
}
void put(Writer& w, const StationOutcomes& o) {
  w.value<std::uint64_t>(o.by_station.size());
  for (const auto& station : o.by_station) w.map(station);
}
void get(Reader& r, StationOutcomes& o) {
  o.by_station.resize(r.value<std::uint64_t>());
  for (auto& station : o.by_station) r.map(station);
}
void put(Writer& w, std::uint64_t count) { w.value(count); }
void get(Reader& r, std::uint64_t& count) { count = r.value<std::uint64_t>(); }
// Every record of a nail (NailRecords::zip: the list merge uses too).
void put(Writer& w, const NailRecords& n) {
  NailRecords::zip(n, n, [&](const auto& record, const auto&) { put(w, record); });
}
void get(Reader& r, NailRecords& n) {
  NailRecords::zip(n, n, [&](auto& record, auto&) { get(r, record); });
}
}  // namespace

std::string pack_chunks(const std::vector<ChunkResult>& chunks, std::size_t count) {
  Writer w;
  w.value<std::uint64_t>(count);
  for (std::size_t i = 0; i < count; ++i) {
    const ChunkResult& c = chunks[i];
    put(w, c);
    w.list(c.tallies, c.tallies.size()), w.list(c.marks, c.marks.size());
  }
  return w.take();
}

std::vector<ChunkResult> unpack_chunks(const std::string& bytes) {
  Reader r(bytes);
  std::vector<ChunkResult> chunks(r.value<std::uint64_t>());
  for (ChunkResult& c : chunks) {
    get(r, c);
    r.list(c.tallies), r.list(c.marks);
  }
  if (!r.done()) throw std::runtime_error("a message between ranks was longer than its contents");
  return chunks;
}

std::string pack_assessment(const Assessment& a) {
  Writer w;
  put(w, a);
  w.value(a.replicates), w.value(a.passed), w.value(a.criterion_passed);
  for (const auto& s : a.shares) w.map(s.counts), w.value(s.total), w.value(s.sum);
  w.value(a.marks), w.value(a.uncounted_marks), w.value(a.fates);
  w.list(a.mark_sample, a.mark_sample.size()), w.value(a.mark_sample_replicates), w.value(a.mark_sample_closed);
  return w.take();
}

void unpack_assessment(const std::string& bytes, Assessment& a) {
  Reader r(bytes);
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

#pragma once
// Bytes passed between the ranks of an MPI job (assess/wire.cpp's chunks and assessments, a
// field comparison's chunk sums). Every rank runs the same executable, so values go as their
// object representation; a message read past its end is an error, never a garbage value.
#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace j232::assess {

class ByteWriter {
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

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
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
  std::size_t position() const { return at_; }  // bytes read so far

 private:
  const std::string& bytes_;
  std::size_t at_ = 0;
};

}  // namespace j232::assess

// A hash table from names to small integers, built once and read often: the registry's types,
// each type's parameters, the compile step's model keys. Looked up by string_view without making
// a std::string, and copyable (it holds its own names), unlike a map keyed by views into the
// table it indexes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace simbob {

class NameTable {
 public:
  /// Adds `name` -> `value`; keeps the first value of a name added twice. Returns whether added.
  bool add(std::string_view name, int value) {
    const uint64_t h = hash(name);
    if (entry(name, h) >= 0) return false;
    append(name, value, h);
    return true;
  }
  /// Maps `name` to `value`, adding the name or replacing the value it had.
  void set(std::string_view name, int value) {
    const uint64_t h = hash(name);
    const int32_t e = entry(name, h);
    if (e >= 0)
      entries_[static_cast<size_t>(e)].value = value;
    else
      append(name, value, h);
  }

  /// The value of `name`, or -1.
  int find(std::string_view name) const { return find(name, hash(name)); }
  /// Same, with `h` == hash(name) computed before (at compile time for a typed parameter name).
  int find(std::string_view name, uint64_t h) const {
    const int32_t e = entry(name, h);
    return e < 0 ? -1 : entries_[static_cast<size_t>(e)].value;
  }

  /// Room for `n` names without growing (a large table's doublings would hold both copies).
  void reserve(size_t n) {
    entries_.reserve(n);
    size_t want = 16;
    while (want < n * 2) want *= 2;
    if (want > slots_.size()) {
      slots_.assign(want, -1);
      for (size_t e = 0; e < entries_.size(); ++e) place(static_cast<int32_t>(e));
    }
  }

  void clear() {
    entries_.clear();
    slots_.clear();
  }
  size_t size() const { return entries_.size(); }

  /// FNV-1a over the name's 64-bit little-endian words, then its tail bytes one by one. Names
  /// are hashed at run time for every type element and key of a large scene (byte by byte that
  /// cost four instructions per letter), and at compile time for typed parameter names: both
  /// ways give the same value (tests/scene/registry_test.cpp).
  static constexpr uint64_t hash(std::string_view s) {
    constexpr uint64_t kPrime = 1099511628211ull;
    uint64_t h = 1469598103934665603ull;
    size_t i = 0;
    for (; i + 8 <= s.size(); i += 8) {
      uint64_t w = 0;
      if (__builtin_is_constant_evaluated()) {
        for (size_t j = 0; j < 8; ++j) w |= static_cast<uint64_t>(static_cast<unsigned char>(s[i + j])) << (8 * j);
      } else {
        __builtin_memcpy(&w, s.data() + i, 8);  // one load
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
        w = __builtin_bswap64(w);  // the little-endian word, as the shifts above make it
#endif
      }
      h = (h ^ w) * kPrime;
      h ^= h >> 32;  // the high bytes of a word reach the low bits
    }
    for (; i < s.size(); ++i) {
      h ^= static_cast<unsigned char>(s[i]);
      h *= kPrime;
    }
    return h ^ (h >> 29);
  }

 private:
  // The index in entries_ of `name` (whose hash is `h`), or -1.
  int32_t entry(std::string_view name, uint64_t h) const {
    if (slots_.empty()) return -1;
    const size_t mask = slots_.size() - 1;
    for (size_t i = h & mask;; i = (i + 1) & mask) {
      const int32_t e = slots_[i];
      if (e < 0) return -1;
      // The whole hashes first: a probe past another name costs one compare, not a memcmp.
      const Entry& en = entries_[static_cast<size_t>(e)];
      if (en.hash == h && en.name == name) return e;
    }
  }
  void append(std::string_view name, int value, uint64_t h) {
    if ((entries_.size() + 1) * 2 > slots_.size()) grow();
    entries_.push_back({std::string(name), value, h});
    place(static_cast<int32_t>(entries_.size() - 1));
  }
  void place(int32_t e) {
    const size_t mask = slots_.size() - 1;
    size_t i = entries_[static_cast<size_t>(e)].hash & mask;
    while (slots_[i] >= 0) i = (i + 1) & mask;
    slots_[i] = e;
  }
  // Open addressing at most half full: a miss ends at the first empty slot within a few probes.
  void grow() {
    slots_.assign(slots_.empty() ? 16 : slots_.size() * 2, -1);
    for (size_t e = 0; e < entries_.size(); ++e) place(static_cast<int32_t>(e));
  }

  struct Entry {
    std::string name;
    int value;
    uint64_t hash;
  };
  std::vector<Entry> entries_;
  std::vector<int32_t> slots_;  ///< index into entries_, -1 empty; size a power of two
};

}  // namespace simbob

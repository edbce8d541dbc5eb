// A small map from vertex numbers to a 32-bit value for one local operation of the simplifier (the
// neighbours of a fan, the link condition of a collapse): open addressing with linear probing over
// a power-of-two table, cleared in O(1) by a generation number. Used instead of per-thread marks
// over every vertex (12 bytes per vertex and thread: 96 bytes per triangle on 16 threads) where
// those would cost too much memory (Simplifier::make_scratch). Not installed.
#pragma once
#include <cstdint>
#include <vector>

namespace interfere::qem {

class VertexMap {
 public:
  /// Empties the map (the entries of earlier generations are ignored).
  void clear() {
    if (++gen_ == 0) {  // wrapped: stale entries could match again
      for (Slot& s : slots_) s.gen = 0;
      gen_ = 1;
    }
    size_ = 0;
    if (slots_.empty()) grow(64);
  }
  /// The value of w, inserted with `init` when absent.
  std::uint32_t& at(std::uint32_t w, std::uint32_t init = 0) {
    if (2 * (size_ + 1) > slots_.size()) grow(2 * slots_.size());
    Slot* s = probe(w);
    if (s->gen != gen_) *s = {w, gen_, init}, ++size_;
    return s->value;
  }
  /// The value of w, or null when absent.
  const std::uint32_t* find(std::uint32_t w) const {
    const Slot* s = const_cast<VertexMap*>(this)->probe(w);
    return s->gen == gen_ ? &s->value : nullptr;
  }

 private:
  struct Slot {
    std::uint32_t key = 0, gen = 0, value = 0;
  };
  // The slot of w, or the free slot where it would go (the load stays at most 1/2).
  Slot* probe(std::uint32_t w) {
    const std::size_t mask = slots_.size() - 1;
    // Fibonacci hashing: the product's high bits (the low ones repeat for strided numbers).
    for (std::size_t i = (w * 0x9E3779B1u) >> shift_;; i = (i + 1) & mask) {
      Slot& s = slots_[i];
      if (s.gen != gen_ || s.key == w) return &s;
    }
  }
  // A larger table holding the current generation's entries.
  void grow(std::size_t n) {
    std::vector<Slot> old;
    old.swap(slots_);
    slots_.assign(n, Slot{});
    shift_ = 32;
    for (std::size_t k = n; k > 1; k >>= 1) --shift_;
    const std::uint32_t g = gen_;
    gen_ = 1;
    size_ = 0;
    for (const Slot& s : old)
      if (s.gen == g && g != 0) at(s.key, s.value);
  }
  std::vector<Slot> slots_;
  std::uint32_t gen_ = 0, shift_ = 32;
  std::size_t size_ = 0;
};

}  // namespace interfere::qem

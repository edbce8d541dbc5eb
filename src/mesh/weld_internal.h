// Internal: the exact-weld kernel shared by weld_exact (double keys, validate.cpp) and the binary
// STL reader (float keys straight from the file bytes, io/stl.cpp), and an uninitialised scratch
// buffer for large temporaries.
//
// Kernel: keys are hashed, scattered stably (parallel blocks, counting sort) into 2^k partitions by
// the top hash bits, and each partition (a few thousand entries, cache-resident) finds duplicates
// with a small open-addressing table. rep[i] is the lowest index with the same key, so the result
// does not depend on the thread count.
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace interfere::weld_detail {

/// Uninitialised array of trivially copyable T. Large ones are 2 MiB aligned and advised for
/// transparent huge pages: first-touch page faults otherwise dominate the cost of streaming passes
/// over hundreds of MB (measured 4-6x slower fread/memset on 4 KiB pages).
template <class T>
class ScratchBuffer {
 public:
  ScratchBuffer() = default;
  explicit ScratchBuffer(std::size_t n) : n_(n) {
    const std::size_t bytes = std::max<std::size_t>(n * sizeof(T), 1);
    constexpr std::size_t kHuge = std::size_t{2} << 20;
    if (bytes >= 2 * kHuge) {
      const std::size_t rounded = (bytes + kHuge - 1) / kHuge * kHuge;
      p_ = static_cast<T*>(std::aligned_alloc(kHuge, rounded));
#if defined(__linux__) && defined(MADV_HUGEPAGE)
      if (p_) ::madvise(p_, rounded, MADV_HUGEPAGE);
#endif
    } else {
      p_ = static_cast<T*>(std::malloc(bytes));
    }
    if (!p_) throw std::bad_alloc();
  }
  ScratchBuffer(ScratchBuffer&& o) noexcept : p_(o.p_), n_(o.n_) {
    o.p_ = nullptr, o.n_ = 0;
  }
  ScratchBuffer& operator=(ScratchBuffer&& o) noexcept {
    std::swap(p_, o.p_);
    std::swap(n_, o.n_);
    return *this;
  }
  ScratchBuffer(const ScratchBuffer&) = delete;
  ScratchBuffer& operator=(const ScratchBuffer&) = delete;
  ~ScratchBuffer() {
    std::free(p_);
  }

  T* data() {
    return p_;
  }
  const T* data() const {
    return p_;
  }
  std::size_t size() const {
    return n_;
  }
  T& operator[](std::size_t i) {
    return p_[i];
  }
  const T& operator[](std::size_t i) const {
    return p_[i];
  }
  /// Forgets the elements past n (keeps the memory).
  void shrink(std::size_t n) {
    n_ = std::min(n, n_);
  }

 private:
  T* p_ = nullptr;
  std::size_t n_ = 0;
};

inline std::uint64_t fmix64(std::uint64_t k) {  // MurmurHash3 finaliser
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdull;
  k ^= k >> 33;
  k *= 0xc4ceb9fe1a85ec53ull;
  k ^= k >> 33;
  return k;
}

using Key32 = std::array<std::uint32_t, 3>;  // float bits
using Key64 = std::array<std::uint64_t, 3>;  // double bits

// Hashes only spread keys over partitions and table slots (equality is always checked on the key),
// so one finaliser over a multiply-combined key is enough.
inline std::uint64_t hash_key(const Key32& k) {
  return fmix64((std::uint64_t{k[0]} | (std::uint64_t{k[1]} << 32)) * 0x9e3779b97f4a7c15ull + k[2]);
}
inline std::uint64_t hash_key(const Key64& k) {
  return fmix64(k[0] * 0x9e3779b97f4a7c15ull + (k[1] ^ (k[1] >> 29)) * 0xbf58476d1ce4e5b9ull +
                k[2]);
}
/// Cheaper hash for the direct-mapped cache of recent keys (top `bits` bits of a multiply).
inline std::size_t cache_slot(const Key32& k, int bits) {
  const std::uint64_t h = ((std::uint64_t{k[0]} | (std::uint64_t{k[1]} << 32)) ^
                           (std::uint64_t{k[2]} * 0xc2b2ae3d27d4eb4full)) *
                          0x9e3779b97f4a7c15ull;
  return static_cast<std::size_t>(h >> (64 - bits));
}
inline std::size_t cache_slot(const Key64& k, int bits) {
  const std::uint64_t h = (k[0] ^ (k[1] * 0xc2b2ae3d27d4eb4full) ^ (k[2] * 0x165667b19e3779f9ull)) *
                          0x9e3779b97f4a7c15ull;
  return static_cast<std::size_t>(h >> (64 - bits));
}

template <class Key>
struct Entry {  // the key travels with its index so that partitions are scanned sequentially
  Key k;
  std::uint32_t index;
};

/// Small inputs: one open-addressing table, serially (the chunk cache and the partitions cost more
/// than they save below about 2^16 keys: a 22,000-vertex CAD part welded in 1.5 ms before).
template <class Key, class KeyOf>
void small_representatives(std::size_t n, const KeyOf& key_of, std::uint32_t* rep) {
  constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
  std::size_t size = 16;
  while (size < 2 * n) size *= 2;
  const std::size_t mask = size - 1;
  // Indices only (4 bytes a slot: a small table, few fresh pages); a probed key is read again.
  std::vector<std::uint32_t> table(size, kEmpty);
  Key k, other;
  for (std::size_t i = 0; i < n; ++i) {
    key_of(i, k);
    for (std::size_t s = hash_key(k) & mask;; s = (s + 1) & mask) {
      const std::uint32_t j = table[s];
      if (j == kEmpty) {
        table[s] = static_cast<std::uint32_t>(i);
        rep[i] = static_cast<std::uint32_t>(i);
        break;
      }
      key_of(j, other);
      if (other[0] == k[0] && other[1] == k[1] && other[2] == k[2]) {
        rep[i] = j;  // the first of its class (keys are visited in index order)
        break;
      }
    }
  }
}

/// rep[i] = lowest j < n with key(j) == key(i), by hash partitioning; key_of(i, Key&) is called
/// twice per index, from several threads. n must be < 2^32.
template <class Key, class KeyOf>
void partitioned_representatives(std::size_t n, const KeyOf& key_of, std::uint32_t* rep) {
  if (n == 0) return;
  int bits = 0;
  while ((n >> bits) > 4096 && bits < 12) ++bits;
  const std::size_t parts = std::size_t{1} << bits;
  auto part_of = [bits](std::uint64_t h) {
    return bits ? static_cast<std::size_t>(h >> (64 - bits)) : 0;
  };

  constexpr std::size_t kBlock = 1 << 15;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::size_t> offset(blocks * parts, 0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t* count = &offset[b * parts];
    Key k;
    for (std::size_t i = b * kBlock, e = std::min(n, i + kBlock); i < e; ++i) {
      key_of(i, k);
      ++count[part_of(hash_key(k))];
    }
  });
  // Exclusive scan, partition-major then block: each partition's entries stay in index order.
  std::vector<std::size_t> part_begin(parts + 1, 0);
  std::size_t run = 0;
  for (std::size_t p = 0; p < parts; ++p) {
    part_begin[p] = run;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t c = offset[b * parts + p];
      offset[b * parts + p] = run;
      run += c;
    }
  }
  part_begin[parts] = run;

  ScratchBuffer<Entry<Key>> entries(n);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t* cursor = &offset[b * parts];
    Key k;
    for (std::size_t i = b * kBlock, e = std::min(n, i + kBlock); i < e; ++i) {
      key_of(i, k);
      Entry<Key>& x = entries[cursor[part_of(hash_key(k))]++];
      x.k = k;
      x.index = static_cast<std::uint32_t>(i);
    }
  });

  constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
  tbb::enumerable_thread_specific<std::vector<std::uint32_t>> tables;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, parts, 1), [&](const auto& range) {
    std::vector<std::uint32_t>& table = tables.local();
    for (std::size_t p = range.begin(); p != range.end(); ++p) {
      const std::size_t lo = part_begin[p], hi = part_begin[p + 1];
      std::size_t size = 16;
      while (size < 2 * (hi - lo)) size *= 2;
      const std::size_t mask = size - 1;
      table.assign(size, kEmpty);
      for (std::size_t j = lo; j < hi; ++j) {
        const Entry<Key>& x = entries[j];
        for (std::size_t s = hash_key(x.k) & mask;; s = (s + 1) & mask) {
          if (table[s] == kEmpty) {
            table[s] = static_cast<std::uint32_t>(j - lo);
            rep[x.index] = x.index;
            break;
          }
          const Entry<Key>& y = entries[lo + table[s]];
          if (y.k[0] == x.k[0] && y.k[1] == x.k[1] && y.k[2] == x.k[2]) {
            rep[x.index] = y.index;  // y came first in this index-ordered partition
            break;
          }
        }
      }
    }
  });
}

/// rep[i] = lowest j < n with key(j) == key(i); key_of(i, Key&) may be called from several threads.
/// Mesh files list neighbouring triangles close together, so most repeated keys are found first in
/// a small direct-mapped cache of recent keys per chunk (links to an earlier equal key); only the
/// remaining candidates, which include every class's first occurrence, go through the global
/// partitioned pass. Links stay inside a chunk, so both ends run chunk-parallel. Up to 2^16 keys:
/// small_representatives.
template <class Key, class KeyOf>
void representatives(std::size_t n, const KeyOf& key_of, std::uint32_t* rep) {
  if (n == 0) return;
  if (n <= (std::size_t{1} << 16)) {
    small_representatives<Key>(n, key_of, rep);
    return;
  }
  constexpr std::size_t kChunk = std::size_t{1} << 16;
  constexpr int kCacheBits = 13;
  constexpr std::size_t kCache = std::size_t{1} << kCacheBits;
  constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::size_t> cand_begin(chunks + 1, 0);
  struct Slot {
    Key k;
    std::uint32_t index;
  };
  tbb::enumerable_thread_specific<std::vector<Slot>> caches;
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    std::vector<Slot>& cache = caches.local();
    cache.assign(kCache, Slot{Key{}, kEmpty});
    std::size_t count = 0;
    Key k;
    for (std::size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; ++i) {
      key_of(i, k);
      Slot& s = cache[cache_slot(k, kCacheBits)];
      if (s.index != kEmpty && s.k[0] == k[0] && s.k[1] == k[1] && s.k[2] == k[2]) {
        rep[i] = s.index;  // an earlier equal key: a link, resolved below
      } else {
        rep[i] = static_cast<std::uint32_t>(i);  // a candidate
        s = Slot{k, static_cast<std::uint32_t>(i)};
        ++count;
      }
    }
    cand_begin[c + 1] = count;
  });
  for (std::size_t c = 0; c < chunks; ++c) cand_begin[c + 1] += cand_begin[c];
  const std::size_t m = cand_begin[chunks];
  ScratchBuffer<std::uint32_t> cand(m);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    std::size_t out = cand_begin[c];
    for (std::size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; ++i) {
      if (rep[i] == i) cand[out++] = static_cast<std::uint32_t>(i);
    }
  });
  ScratchBuffer<std::uint32_t> cand_rep(m);
  partitioned_representatives<Key>(
      m, [&](std::size_t j, Key& k) { key_of(cand[j], k); }, cand_rep.data());
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    std::size_t j = cand_begin[c];
    for (std::size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; ++i) {
      const std::uint32_t link = rep[i];
      rep[i] = link == i ? cand[cand_rep[j++]] : rep[link];  // link < i is already final
    }
  });
}

}  // namespace interfere::weld_detail

#pragma once
// A spatial hash of particles or boxes for the contact effects (self_collision.cpp,
// contact.cpp): entries counting-sorted into a power-of-two table of buckets,
// each entry keyed by its cell so other cells sharing a bucket are skipped.
// Private to src/sim/effects.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "vgd/sim/types.hpp"

namespace vgd::sim::detail {

class SpatialHash {
 public:
  void build(const VecX& x, int n, double cell) {
    inv_cell_ = 1.0 / cell;
    std::size_t size = 1;
    while (size < 2 * static_cast<std::size_t>(n)) size <<= 1;
    mask_ = size - 1;
    start_.assign(size + 1, 0);
    key_.resize(n);
    bucket_.resize(n);
    for (int i = 0; i < n; ++i) {
      const auto c = cell_of(at(x, i));
      key_[i] = key(c);
      bucket_[i] = hash(c);
      ++start_[bucket_[i] + 1];
    }
    for (std::size_t b = 0; b < size; ++b) start_[b + 1] += start_[b];
    items_.resize(n);
    item_key_.resize(n);
    fill_.assign(start_.begin(), start_.end() - 1);
    for (int i = 0; i < n; ++i) {
      const std::size_t e = fill_[bucket_[i]]++;
      items_[e] = i;
      item_key_[e] = key_[i];
    }
    boxes_ = false;
  }

  // Every particle's box [lo_i, hi_i] (its motion over the step, grown by a
  // pad) into every cell it meets: entries (particle, cell key), counting-sorted
  // into buckets. A query may then meet a particle more than once.
  void build_boxes(const VecX& x0, const VecX& x1, int n, double cell, double pad) {
    all_.resize(n);
    for (int i = 0; i < n; ++i) all_[i] = i;
    build_boxes(x0, x1, all_, cell, pad);
  }
  // The same for the particles listed only.
  void build_boxes(const VecX& x0, const VecX& x1, const std::vector<int>& particles, double cell, double pad) {
    build_items(static_cast<int>(particles.size()), cell, [&](int k, Vec3& lo, Vec3& hi) {
      const int i = particles[k];
      lo = at(x0, i).cwiseMin(at(x1, i)) - Vec3::Constant(pad);
      hi = at(x0, i).cwiseMax(at(x1, i)) + Vec3::Constant(pad);
      return i;
    });
  }

  // Any items by their boxes: box(k, lo, hi) fills item k's box and returns
  // the id stored for it (for_each_in_box hands back ids).
  template <class Box>
  void build_items(int count, double cell, Box&& box) {
    inv_cell_ = 1.0 / cell;
    entries_.clear();
    for (int k = 0; k < count; ++k) {
      Vec3 lo, hi;
      const int id = box(k, lo, hi);
      const auto a = cell_of(lo), b = cell_of(hi);
      for (int z = a[2]; z <= b[2]; ++z)
        for (int j = a[1]; j <= b[1]; ++j)
          for (int l = a[0]; l <= b[0]; ++l) entries_.push_back({id, {l, j, z}});
    }
    const std::size_t m = entries_.size();
    std::size_t size = 1;
    while (size < 2 * std::max<std::size_t>(m, 1)) size <<= 1;
    mask_ = size - 1;
    start_.assign(size + 1, 0);
    key_.resize(m);
    bucket_.resize(m);
    for (std::size_t e = 0; e < m; ++e) {
      key_[e] = key(entries_[e].second);
      bucket_[e] = hash(entries_[e].second);
      ++start_[bucket_[e] + 1];
    }
    for (std::size_t b = 0; b < size; ++b) start_[b + 1] += start_[b];
    items_.resize(m);
    item_key_.resize(m);
    fill_.assign(start_.begin(), start_.end() - 1);
    for (std::size_t e = 0; e < m; ++e) {
      const std::size_t at_ = fill_[bucket_[e]]++;
      items_[at_] = entries_[e].first;
      item_key_[at_] = key_[e];
    }
    boxes_ = true;
  }

  std::array<int, 3> cell_of(const Vec3& p) const {
    return {static_cast<int>(std::floor(p.x() * inv_cell_)), static_cast<int>(std::floor(p.y() * inv_cell_)),
            static_cast<int>(std::floor(p.z() * inv_cell_))};
  }

  // Calls f(i) once for every particle whose cell meets the box [lo, hi].
  template <class F>
  void for_each_in_box(const Vec3& lo, const Vec3& hi, F&& f) const {
    const auto a = cell_of(lo), b = cell_of(hi);
    for (int k = a[2]; k <= b[2]; ++k)
      for (int j = a[1]; j <= b[1]; ++j)
        for (int i = a[0]; i <= b[0]; ++i) {
          const std::array<int, 3> c{i, j, k};
          const std::size_t h = hash(c);
          const std::uint64_t kc = key(c);
          for (std::size_t s = start_[h]; s < start_[h + 1]; ++s)
            if (item_key_[s] == kc) f(items_[s]);  // other cells sharing the bucket: skip
        }
  }

 private:
  std::size_t hash(const std::array<int, 3>& c) const {
    const std::uint64_t h = static_cast<std::uint64_t>(c[0]) * 73856093u ^
                            static_cast<std::uint64_t>(c[1]) * 19349663u ^
                            static_cast<std::uint64_t>(c[2]) * 83492791u;
    return static_cast<std::size_t>(h) & mask_;
  }
  // The cell as one integer (21 bits per axis: ±10⁶ cells, ±17 km at 1.7 cm),
  // compared instead of three ints.
  static std::uint64_t key(const std::array<int, 3>& c) {
    constexpr std::uint64_t m = (1u << 21) - 1;
    return (static_cast<std::uint64_t>(c[0]) & m) | ((static_cast<std::uint64_t>(c[1]) & m) << 21) |
           ((static_cast<std::uint64_t>(c[2]) & m) << 42);
  }
  double inv_cell_ = 1.0;
  std::size_t mask_ = 0;
  std::vector<std::size_t> start_, fill_, bucket_;
  std::vector<int> items_;
  std::vector<std::uint64_t> key_, item_key_;
  std::vector<std::pair<int, std::array<int, 3>>> entries_;
  std::vector<int> all_;
  bool boxes_ = false;
};

}  // namespace vgd::sim::detail

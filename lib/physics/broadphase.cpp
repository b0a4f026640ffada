// HashSpacePairs: dHashSpace's pairs in dHashSpace's order, by a sweep (see broadphase.h).
#include "broadphase.h"

#include "workers.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>

namespace simbob {

namespace {

void ignorePair(void*, dGeomID, dGeomID) {}

constexpr dReal kMaxCell = 16777216;  // 2^24

bool finite(const dReal b[6]) {
  for (int i = 0; i < 6; ++i) {
    if (!(b[i] > -dInfinity && b[i] < dInfinity)) return false;
  }
  return true;
}

/// dHashSpace's level of a box: the smallest L with 2^L >= its largest extent (frexp's exponent).
int boxLevel(const dReal b[6]) {
  dReal q = b[1] - b[0];
  q = std::max(q, b[3] - b[2]);
  q = std::max(q, b[5] - b[4]);
  int level = 0;
  std::frexp(q, &level);
  return level;
}

/// What dHashSpace tests before it reports a pair: not one body, matching category bits,
/// overlapping boxes (touching counts).
template <typename Box>
bool meets(const Box& a, const Box& b) {
  if (a.body == b.body && a.body) return false;
  if (((a.category & b.collide) || (b.category & a.collide)) == 0) return false;
  return !(a.aabb[0] > b.aabb[1] || a.aabb[1] < b.aabb[0] || a.aabb[2] > b.aabb[3] || a.aabb[3] < b.aabb[2] ||
           a.aabb[4] > b.aabb[5] || a.aabb[5] < b.aabb[4]);
}

/// A cell index at a level `up` levels higher: dHashSpace halves (arithmetic shift) once a level.
int cellAbove(int cell, int up) { return cell >> std::min(up, 31); }

/// dHashSpace's bucket of a cell (level, x, y, z) is (B + z) mod (table size), with
/// B = u32(level)*1000 + u32(x)*100 + u32(y)*10, computed as it walks the z of a column from the
/// first z of the box it files or looks up, z0: its unsigned sum B + z0 wraps past 2^64 when
/// B + z0 < 0 (B is 0 for level = x = y = 0, so z0 = -1 wraps), and then the whole column lands
/// 2^64 mod (table size) buckets further on. A box filed from a wrapped sum is not found from an
/// unwrapped one and the other way round: that pair is not met in that column.
bool wraps(int level, int x, int y, int z0) {
  const uint64_t base = uint64_t(uint32_t(level)) * 1000 + uint64_t(uint32_t(x)) * 100 + uint64_t(uint32_t(y)) * 10;
  return int64_t(base) + z0 < 0;  // base < 2^44: no overflow
}

/// The axis along which the boxes overlap least: the sum of their extents over the spread of
/// their lower bounds, smallest.
template <typename Box>
int sweepAxis(const std::vector<Box>& boxes) {
  int best = 0;
  double bestRatio = INFINITY;
  for (int a = 0; a < 3; ++a) {
    double sum = 0, lo = INFINITY, hi = -INFINITY;
    const size_t i = 2 * static_cast<size_t>(a);
    for (const Box& b : boxes) {
      sum += b.aabb[i + 1] - b.aabb[i];
      lo = std::min(lo, b.aabb[i]);
      hi = std::max(hi, b.aabb[i]);
    }
    const double ratio = hi > lo ? sum / (hi - lo) : INFINITY;
    if (ratio < bestRatio) {
      bestRatio = ratio;
      best = a;
    }
  }
  return best;
}

}  // namespace

HashSpacePairs::~HashSpacePairs() {
  if (cleaner_) dGeomDestroy(cleaner_);
}

void HashSpacePairs::collide(dSpaceID space, void* data, dNearCallback* callback, WorkerPool* pool, size_t grain) {
  if (dSpaceGetNumGeoms(space) < 2) return;  // dHashSpace returns before anything else
  // dHashSpace first recomputes the boxes of the geoms that moved and marks them clean, which
  // decides where they go in the space's list the next time they move. The public way to do
  // exactly that is dSpaceCollide2 of the space against a geom that collides with nothing: it
  // cleans the geoms, then finds no category bits in common with any of them.
  if (!cleaner_) {
    cleaner_ = dCreateSphere(nullptr, 1);
    dGeomSetCategoryBits(cleaner_, 0);
    dGeomSetCollideBits(cleaner_, 0);
  }
  dSpaceCollide2(cleaner_, reinterpret_cast<dGeomID>(space), nullptr, &ignorePair);
  if (!gather(space)) {  // a box this sweep cannot place like dHashSpace: let dHashSpace do it
    dSpaceCollide(space, data, callback);
    return;
  }
  findPairs(pool, grain);
  for (const Pair& p : pairs_)
    callback(data, hash_[static_cast<size_t>(p.a)].geom, hash_[static_cast<size_t>(p.b)].geom);
  for (const Box& a : hash_) {
    for (const Box& b : big_) {
      if (meets(a, b)) callback(data, a.geom, b.geom);
    }
  }
  for (size_t i = 0; i < big_.size(); ++i) {
    for (size_t j = i + 1; j < big_.size(); ++j) {
      if (meets(big_[i], big_[j])) callback(data, big_[i].geom, big_[j].geom);
    }
  }
}

bool HashSpacePairs::firstMeeting(const Box& low, const Box& high, Pair& p) {
  // low's cells at high's level: dHashSpace halves its cell indices once per level up.
  const int up = high.level - low.level;
  int lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::max(cellAbove(low.lo[k], up), high.lo[k]);
    hi[k] = std::min(cellAbove(low.hi[k], up), high.hi[k]);
  }
  const int lowZ0 = cellAbove(low.lo[2], up);
  for (int x = lo[0]; x <= hi[0]; ++x) {
    for (int y = lo[1]; y <= hi[1]; ++y) {
      if (wraps(high.level, x, y, lowZ0) != wraps(high.level, x, y, high.lo[2])) continue;
      p.level = high.level;
      p.cell[0] = x;
      p.cell[1] = y;
      p.cell[2] = lo[2];
      return true;
    }
  }
  return false;  // dHashSpace never meets them: no call, though their boxes overlap
}

bool HashSpacePairs::gather(dSpaceID space) {
  int minLevel = 0, maxLevel = 0;
  dHashSpaceGetLevels(space, &minLevel, &maxLevel);
  hash_.clear();
  big_.clear();
  const int n = dSpaceGetNumGeoms(space);
  for (int i = 0; i < n; ++i) {  // from 0: dSpaceGetGeom walks the list once, in its order
    dGeomID g = dSpaceGetGeom(space, i);
    if (!dGeomIsEnabled(g)) continue;
    Box box{};
    box.geom = g;
    box.body = dGeomGetBody(g);
    box.category = dGeomGetCategoryBits(g);
    box.collide = dGeomGetCollideBits(g);
    dGeomGetAABB(g, box.aabb);
    for (int k = 0; k < 6; ++k) {
      if (std::isnan(box.aabb[k])) return false;
    }
    if (!finite(box.aabb)) {
      big_.push_back(box);
      continue;
    }
    box.level = std::max(boxLevel(box.aabb), minLevel);
    if (box.level > maxLevel) {
      big_.push_back(box);
      continue;
    }
    const dReal recip = 1 / std::ldexp(dReal(1), box.level);  // exact: a power of two
    for (int a = 0; a < 3; ++a) {
      const dReal lo = std::floor(box.aabb[2 * static_cast<size_t>(a)] * recip);
      const dReal hi = std::floor(box.aabb[2 * static_cast<size_t>(a) + 1] * recip);
      // dHashSpace's cell arithmetic stays exact for cells within +-2^24 (its int products).
      if (!(lo >= -kMaxCell && hi <= kMaxCell)) return false;
      box.lo[a] = static_cast<int>(lo);
      box.hi[a] = static_cast<int>(hi);
    }
    hash_.push_back(box);
  }
  return true;
}

void HashSpacePairs::sweep(size_t begin, size_t end, std::vector<Pair>& out) const {
  const size_t n = swept_.size();
  for (size_t i = begin; i < end; ++i) {
    const Span& s = swept_[i];
    for (size_t j = i + 1; j < n; ++j) {
      const Span& t = swept_[j];
      if (t.lo > s.hi) break;
      // meets() tests these too; most boxes that overlap along the sweep axis in a dense scene
      // fail here, on the spans at hand, before their boxes are read.
      if (t.lo1 > s.hi1 || t.hi1 < s.lo1 || t.lo2 > s.hi2 || t.hi2 < s.lo2) continue;
      const Box& a = hash_[static_cast<size_t>(s.box)];
      const Box& b = hash_[static_cast<size_t>(t.box)];
      if (!meets(a, b)) continue;
      // Met from the box of the lower level, the earlier one at equal levels.
      const bool aFirst = a.level < b.level || (a.level == b.level && s.box < t.box);
      Pair p{aFirst ? s.box : t.box, aFirst ? t.box : s.box, 0, {}};
      if (firstMeeting(aFirst ? a : b, aFirst ? b : a, p)) out.push_back(p);
    }
  }
}

void HashSpacePairs::findPairs(WorkerPool* pool, size_t grain) {
  pairs_.clear();
  const size_t n = hash_.size();
  const size_t axis = 2 * static_cast<size_t>(sweepAxis(hash_));  // the axis's lower bound in aabb
  const size_t axis1 = (axis + 2) % 6, axis2 = (axis + 4) % 6;
  // Sorted as (lower bound, box) pairs, a quarter of a span each; then the spans in that order.
  order_.resize(n);
  for (size_t i = 0; i < n; ++i) order_[i] = {hash_[i].aabb[axis], static_cast<int>(i)};
  std::sort(order_.begin(), order_.end(), [](const std::pair<dReal, int>& x, const std::pair<dReal, int>& y) {
    return x.first < y.first || (x.first == y.first && x.second < y.second);
  });
  swept_.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const int i = order_[k].second;
    const dReal* b = hash_[static_cast<size_t>(i)].aabb;
    swept_[k] = {b[axis], b[axis + 1], b[axis1], b[axis1 + 1], b[axis2], b[axis2 + 1], i};
  }
  if (pool) {
    // Each chunk of the sorted boxes sweeps into its own list; the lists joined in chunk order
    // are the serial sweep's list, and the sort below orders the pairs totally anyway.
    const size_t chunks = pool->chunks(n, grain);
    if (chunkPairs_.size() < chunks) chunkPairs_.resize(chunks);
    pool->run(n, grain, [&](size_t c, size_t begin, size_t end, int) {
      chunkPairs_[c].clear();
      sweep(begin, end, chunkPairs_[c]);
    });
    for (size_t c = 0; c < chunks; ++c) pairs_.insert(pairs_.end(), chunkPairs_[c].begin(), chunkPairs_[c].end());
  } else {
    sweep(0, n, pairs_);
  }
  std::sort(pairs_.begin(), pairs_.end(), [](const Pair& x, const Pair& y) {
    if (x.a != y.a) return x.a < y.a;
    if (x.level != y.level) return x.level < y.level;
    for (int k = 0; k < 3; ++k) {
      if (x.cell[k] != y.cell[k]) return x.cell[k] < y.cell[k];
    }
    return x.b > y.b;  // a cell's boxes are met latest first
  });
}

}  // namespace simbob

// The broad phase of the default collision space (Space Hash): the pairs ODE's dHashSpace
// reports, in the order it reports them, found without its per-step hash table.
//
// Why: the order of the pairs is the order of the contact joints, and QuickStep's result depends
// on that order, so every golden trajectory depends on it. dHashSpace finds the pairs by walking,
// for every geom, every cell level from the geom's own up to the largest geom's, with a hash
// table and an n*n bit table built on the heap at every step. In a scene of small robots among
// long walls (bench/sensor_bench.py) that walk was a third of the run. HashSpacePairs finds the
// overlapping pairs by sweeping sorted boxes along one axis and then puts them in dHashSpace's
// order, which follows from its algorithm (ODE 0.16, collision_space.cpp):
//
//  - the geoms, in the space's list order, are the "hash boxes" (their level is at most the
//    space's maximum level) and the "big boxes" (larger, or infinite like planes);
//  - a box's level L is the smallest with 2^L >= its largest extent (at least the space's
//    minimum level); at level L it occupies the cells floor(aabb / 2^L);
//  - for each hash box A in order, for each level from A's to the largest, for each cell A
//    covers at that level (x, then y, then z), the boxes of that level in that cell, latest first,
//    are tested against A -- each pair once, the first time it is met;
//  - then every hash box against every big box, then the big boxes against each other.
//
// So a pair of hash boxes is met from the box of the lower level (of the earlier one, at equal
// levels), at the other's level, in the first cell they share, which is the lower corner of the
// overlap of their cell ranges -- unless dHashSpace's hash of that cell's column differs between
// the two boxes (near the origin; see `wraps` in broadphase.cpp), when it is the next shared
// column where it does not, or none: such a pair is never reported. The pairs reported are those whose boxes overlap and whose
// bodies and category bits allow it, as dHashSpace tests them; the AABBTest refinement only
// exists for user geom classes, which simbob does not create. tests/physics_ode/broadphase_test
// checks the sequence against dSpaceCollide's on random scenes, step after step.
#pragma once

#include <ode/ode.h>

#include <cstddef>
#include <utility>
#include <vector>

namespace simbob {

class WorkerPool;

class HashSpacePairs {
 public:
  HashSpacePairs() = default;
  HashSpacePairs(const HashSpacePairs&) = delete;
  HashSpacePairs& operator=(const HashSpacePairs&) = delete;
  ~HashSpacePairs();

  /// What dSpaceCollide(space, data, callback) does for a dHashSpace (its levels included): the
  /// same calls in the same order, and the space left as it would leave it (geoms clean). With
  /// a pool the sweep is split among its threads in chunks of `grain` boxes at least; the pairs
  /// and their order do not change.
  void collide(dSpaceID space, void* data, dNearCallback* callback, WorkerPool* pool = nullptr, size_t grain = 256);

 private:
  struct Box {
    dGeomID geom;
    dBodyID body;
    unsigned long category, collide;
    dReal aabb[6];
    int level;  ///< cell level (hash boxes)
    int lo[3];  ///< first cell at `level`, per axis (hash boxes)
    int hi[3];  ///< last cell at `level`, per axis (hash boxes)
  };
  struct Pair {
    int a, b;     ///< hash box indices: a meets b
    int level;    ///< b's level: where a meets b
    int cell[3];  ///< the first cell they share at that level
  };

  /// The space's enabled geoms as hash and big boxes, in its list order; false for a box whose
  /// cells do not fit an int or whose bounds are NaN (collide then leaves it to dHashSpace).
  bool gather(dSpaceID space);
  /// The overlapping pairs of hash boxes, in dHashSpace's order.
  void findPairs(WorkerPool* pool, size_t grain);
  /// A hash box's extent along the sweep axis and the two others, kept in sweep order side by
  /// side: the sweep reads these (a dense scene tests each box against many) instead of the
  /// boxes themselves, scattered in the space's order.
  struct Span {
    dReal lo, hi;    ///< along the sweep axis
    dReal lo1, hi1;  ///< along the next axis
    dReal lo2, hi2;  ///< along the last axis
    int box;         ///< index into hash_
  };
  /// The pairs met sweeping from swept_[begin, end) (each box against those after it), into out.
  void sweep(size_t begin, size_t end, std::vector<Pair>& out) const;
  /// Where dHashSpace meets `high` looking from `low` (low's level <= high's): p.level and
  /// p.cell; false if it never does.
  static bool firstMeeting(const Box& low, const Box& high, Pair& p);

  dGeomID cleaner_ = nullptr;  ///< a geom in no space that collides with nothing (see collide)
  std::vector<Box> hash_;
  std::vector<Box> big_;
  std::vector<std::pair<dReal, int>> order_;  ///< (lower bound along the sweep axis, box), sorted
  std::vector<Span> swept_;                   ///< the hash boxes in that order
  std::vector<Pair> pairs_;
  std::vector<std::vector<Pair>> chunkPairs_;  ///< each sweep chunk's pairs (with a pool)
};

}  // namespace simbob

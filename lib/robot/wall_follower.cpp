// RCWallFollower (simbob's own): every Period it reads its RCLaserScanner and steers its
// RC2DMotionControl along a wall on one Side at Distance. Ray k of the scanner has the bearing
// b_k in the body's frame (its direction projected on the body's ground plane, from the forward
// axis +X, counter-clockwise seen from above); sigma = +1 for Side Left, -1 for Right.
//   side distance  d = min r_k over the rays with sigma b_k in [45, 170] degrees
//                      (the nearest wall point on that side: its perpendicular distance);
//   front distance g = min r_k cos b_k over the rays with |b_k| < 25 degrees
//                      (narrow: a side wall s away reads at least s cot 20 = 2.7 s there, so one
//                      at 0.55 Distance or more never counts as a wall ahead).
// With e = d - Distance and e' its change since the last reading over the Period (clamped to
// +-Speed, 0 at the first reading), a PD law keeps the wall at Distance:
//   w = sigma clamp(Kp e + Kd e', -TurnRate, TurnRate),  Kp = W^2 / Speed, Kd = 2 W / Speed,
// W = 2 Speed / Distance. For small angles e'' = -Speed w sigma, so e'' + 2 W e' + W^2 e = 0: the
// error dies out critically damped within a few Distances of travel. An outer corner (the wall
// ends: d grows) turns it round the wall's end towards its side. An inner corner (a wall ahead,
// g < 1.5 Distance) overrides: it turns away from its wall side at TurnRate and slows down,
//   v = Speed clamp((g - Distance) / Distance, 0, 1), w = -sigma TurnRate;
// otherwise v = Speed.
#include <algorithm>
#include <cmath>

#include "robot/controllers.h"
#include "simbob/cr_math.h"
#include "simbob/physics.h"
#include "simbob/transform.h"

namespace simbob::robot {

namespace {

class WallFollower : public Party {
 public:
  WallFollower(const WallFollowerDef& c, const Model& model, MotionControl2D* motion)
      : motion_(motion),
        scanner_(c.scanner),
        sigma_(c.side),
        distance_(c.wall_distance),
        speed_(c.speed),
        turn_rate_(c.turn_rate),
        period_(c.period),
        tick_(c.period) {
    const SensorDef& s = model.sensors[static_cast<size_t>(scanner_)];
    const double deg = kPi / 180;
    for (int k = 0; k < s.rays; ++k) {
      const double a = scannerRayAngle(s, k);
      const Vec3 d = rotate(s.pose.q, Vec3{-crSin(a), 0, -crCos(a)});
      const double b = crAtan2(-d[2], d[0]);
      if (sigma_ * b >= 45 * deg && sigma_ * b <= 170 * deg) side_rays_.push_back(k);
      if (std::fabs(b) < 25 * deg) {
        front_rays_.push_back(k);
        front_cos_.push_back(crCos(b));
      }
    }
    max_range_ = s.max_range;
  }
  SimTime first() override { return 0; }
  SimTime onGrant(SimTime now, World& world) override {
    const std::vector<double>& r = world.sensorReading(scanner_);
    double d = max_range_, g = max_range_;
    for (int k : side_rays_) d = std::min(d, r[static_cast<size_t>(k)]);
    for (size_t i = 0; i < front_rays_.size(); ++i)
      g = std::min(g, r[static_cast<size_t>(front_rays_[i])] * front_cos_[i]);
    const double e = d - distance_;
    const double de = first_ ? 0.0 : std::clamp((e - last_e_) / period_, -speed_, speed_);
    first_ = false;
    last_e_ = e;
    double v = speed_, w;
    if (g < 1.5 * distance_) {
      v = speed_ * std::clamp((g - distance_) / distance_, 0.0, 1.0);
      w = -sigma_ * turn_rate_;
    } else {
      const double wn = 2 * speed_ / distance_;
      w = sigma_ * std::clamp(wn * wn / speed_ * e + 2 * wn / speed_ * de, -turn_rate_, turn_rate_);
    }
    motion_->setMotion(v, w, world);
    return tick_.next(now);
  }

 private:
  MotionControl2D* motion_;
  int scanner_;
  int sigma_;
  double distance_, speed_, turn_rate_, period_;
  Periodic tick_;
  std::vector<int> side_rays_, front_rays_;
  std::vector<double> front_cos_;
  double max_range_ = 0;
  double last_e_ = 0;
  bool first_ = true;
};

}  // namespace

std::unique_ptr<Party> makeWallFollower(const WallFollowerDef& c, const Model& model, MotionControl2D* motion) {
  return std::make_unique<WallFollower>(c, model, motion);
}

}  // namespace simbob::robot

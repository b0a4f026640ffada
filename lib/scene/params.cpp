// One parameter value from text: the guide 4.3 parser plus the checks every parameter gets
// (magnitude, range). The scene loader and `--set` overrides both read values through here.
#include <cmath>
#include <type_traits>

#include "simbob/error.h"
#include "simbob/registry.h"
#include "scene/limits.h"

namespace simbob {

namespace {

constexpr double kMaxMagnitude = kMaxValueMagnitude;  // scene/limits.h

// The largest finite absolute number inside a value (infinities are checked by the parser).
double largestFinite(const Value& v) {
  double big = 0;
  auto take = [&](double d) {
    if (std::isfinite(d)) big = std::max(big, std::fabs(d));
  };
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, double>)
          take(x);
        else if constexpr (std::is_same_v<T, int64_t>)
          take(static_cast<double>(x));
        else if constexpr (std::is_same_v<T, Triple>)
          for (double d : x) take(d);
        else if constexpr (std::is_same_v<T, Vector4>)
          for (double d : x.v) take(d);
        else if constexpr (std::is_same_v<T, Quaternion>)
          for (double d : x.q) take(d);
        else if constexpr (std::is_same_v<T, Pose>) {
          for (double d : x.pos) take(d);
          for (double d : x.euler_deg) take(d);
        } else if constexpr (std::is_same_v<T, Matrix4>)
          for (double d : x.m) take(d);
        else if constexpr (std::is_same_v<T, Cuboid>) {
          for (double d : x.a) take(d);
          for (double d : x.b) take(d);
        }
      },
      v);
  return big;
}

const char* rangeText(Range r) {
  switch (r) {
    case Range::Any:
      return "";
    case Range::Positive:
      return "must be > 0";
    case Range::NonNegative:
      return "must be >= 0";
    case Range::Unit:
      return "must be in [0, 1]";
  }
  return "";
}

bool inRange(Range r, double v) {
  switch (r) {
    case Range::Any:
      return true;
    case Range::Positive:
      return v > 0;
    case Range::NonNegative:
      return v >= 0;
    case Range::Unit:
      return v >= 0 && v <= 1;
  }
  return true;
}

}  // namespace

ParseResult parseParam(const ParamSpec& p, std::string_view text) {
  // Most values of a large scene are plain numbers: one that parses, has no blanks around it,
  // and passes the checks below is taken at once; anything else goes the general way, which
  // says what is wrong.
  double d = 0;
  if (p.type == ValueType::Number && parseNumberValue(text, p.allow_infinite, &d) &&
      !(std::isfinite(d) && std::fabs(d) > kMaxMagnitude) && inRange(p.range, d))
    return ParseResult{Value(d), {}};
  ParseOptions opts;
  opts.allow_infinite = p.allow_infinite;
  ParseResult r = parseValue(p.type, text, p.table, opts);
  if (!r) {
    r.error = "parameter '" + p.name + "': " + r.error;
    return r;
  }
  // Absurd magnitudes (1e300 m) overflow inertia and contact math inside ODE: refuse them here.
  if (double big = largestFinite(*r.value); big > kMaxMagnitude) {
    return {std::nullopt, "parameter '" + p.name + "': " + formatNumber(big) + " is beyond the supported magnitude " +
                              formatNumber(kMaxMagnitude)};
  }
  if (p.range != Range::Any) {
    double v = 0;
    if (auto* d = std::get_if<double>(&*r.value)) v = *d;
    if (auto* i = std::get_if<int64_t>(&*r.value)) v = static_cast<double>(*i);
    if (!inRange(p.range, v))
      return {std::nullopt, "parameter '" + p.name + "' " + rangeText(p.range) + ", got '" + quoteInput(text) + "'"};
  }
  return r;
}

}  // namespace simbob

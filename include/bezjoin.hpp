// bezjoin.hpp: a small header-only C++17 wrapper over the C ABI in bezjoin.h.
//
// * bezjoin::Curve owns one BzjCurve handle (move-only; released with
//   bzj_curve_free in the destructor).
// * Every failed call throws bezjoin::Error, which carries the BzjStatus and the
//   library's message (bzj_last_error(), naming the offending argument).
// * Control points and derivative blocks are row-major std::vector<double>,
//   exactly as in the C contract: point i, coordinate c at [i * dim + c].
//
// The operation groups (connect, fillet/intersect, merge, Lagrange spline) are
// compiled only when BEZJOIN_HAS_<GROUP> is non-zero. They default to 1 (all of
// the contract in shared/spec/c-api.md); a host building against an older
// bezjoin.h that lacks a group may define the macro to 0. (cpp-demo/ does not:
// its CMakeLists.txt stops with an error when the header lacks a group, so no
// check can silently drop out of the demo.)
//
// Contract: shared/spec/c-api.md. Mathematics: shared/spec/mathematics.md.

#ifndef BEZJOIN_HPP
#define BEZJOIN_HPP

#include "bezjoin.h"

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#ifndef BEZJOIN_HAS_CONNECT
#define BEZJOIN_HAS_CONNECT 1
#endif
#ifndef BEZJOIN_HAS_FILLET
#define BEZJOIN_HAS_FILLET 1
#endif
#ifndef BEZJOIN_HAS_MERGE
#define BEZJOIN_HAS_MERGE 1
#endif
#ifndef BEZJOIN_HAS_LAGRANGE
#define BEZJOIN_HAS_LAGRANGE 1
#endif

namespace bezjoin {

/// A failed bezjoin call: the status code and the library's message.
class Error : public std::runtime_error {
public:
    Error(BzjStatus status, const std::string& operation)
        : std::runtime_error(operation + ": " + bzj_status_name(static_cast<int32_t>(status)) +
                             ": " + bzj_last_error()),
          status_(status) {}

    /// The status the C function returned (never BZJ_OK).
    BzjStatus status() const noexcept { return status_; }

private:
    BzjStatus status_;
};

/// Throw bezjoin::Error unless `status` is BZJ_OK. Reads bzj_last_error() at
/// once, while the message is still the one of this call.
inline void check(BzjStatus status, const char* operation) {
    if (status != BZJ_OK) {
        throw Error(status, operation);
    }
}

/// The library version string, "MAJOR.MINOR.PATCH".
inline std::string version() { return bzj_version(); }

/// An owning, move-only handle to an immutable Bezier curve.
class Curve {
public:
    /// An empty handle (owns nothing).
    Curve() noexcept = default;

    /// Take ownership of a handle returned by the C API (may be NULL).
    explicit Curve(BzjCurve* handle) noexcept : handle_(handle) {}

    /// A curve of degree `degree` in dimension `dim` from `(degree + 1) * dim`
    /// row-major coordinates.
    Curve(std::size_t dim, std::size_t degree, const std::vector<double>& points) {
        check(bzj_curve_new(dim, degree, points.data(), points.size(), &handle_), "bzj_curve_new");
    }

    Curve(const Curve&) = delete;
    Curve& operator=(const Curve&) = delete;
    Curve(Curve&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
    Curve& operator=(Curve&& other) noexcept {
        if (this != &other) {
            bzj_curve_free(handle_);
            handle_ = std::exchange(other.handle_, nullptr);
        }
        return *this;
    }
    ~Curve() { bzj_curve_free(handle_); }

    /// The borrowed C handle (still owned by this object).
    const BzjCurve* get() const noexcept { return handle_; }
    /// Give up ownership: the caller must bzj_curve_free the result.
    BzjCurve* release() noexcept { return std::exchange(handle_, nullptr); }
    explicit operator bool() const noexcept { return handle_ != nullptr; }

    std::size_t degree() const {
        std::size_t out = 0;
        check(bzj_curve_degree(handle_, &out), "bzj_curve_degree");
        return out;
    }

    std::size_t dim() const {
        std::size_t out = 0;
        check(bzj_curve_dim(handle_, &out), "bzj_curve_dim");
        return out;
    }

    /// The `(degree + 1) * dim` row-major control points.
    std::vector<double> points() const {
        std::vector<double> out((degree() + 1) * dim());
        check(bzj_curve_points(handle_, out.data(), out.size()), "bzj_curve_points");
        return out;
    }

    /// Value and derivatives 0..max_order at `t`: row k (dim doubles) is the
    /// k-th derivative.
    std::vector<double> eval(double t, std::size_t max_order = 0) const {
        std::vector<double> out((max_order + 1) * dim());
        check(bzj_curve_eval(handle_, t, max_order, out.data(), out.size()), "bzj_curve_eval");
        return out;
    }

    /// As eval(), into a caller buffer of `out_len >= (max_order + 1) * dim`
    /// doubles (no allocation; for hot loops).
    void eval_into(double t, std::size_t max_order, double* out, std::size_t out_len) const {
        check(bzj_curve_eval(handle_, t, max_order, out, out_len), "bzj_curve_eval");
    }

    /// The same curve written with degree `new_degree >= degree()` (exact).
    Curve elevate(std::size_t new_degree) const {
        BzjCurve* out = nullptr;
        check(bzj_curve_elevate(handle_, new_degree, &out), "bzj_curve_elevate");
        return Curve(out);
    }

    /// The pieces on [0, t] and [t, 1], each reparametrised to [0, 1].
    std::pair<Curve, Curve> split(double t) const {
        BzjCurve* left = nullptr;
        BzjCurve* right = nullptr;
        check(bzj_curve_split(handle_, t, &left, &right), "bzj_curve_split");
        return {Curve(left), Curve(right)};
    }

    /// s -> c(a + (b - a) s), any finite a, b (extrapolation allowed).
    Curve segment(double a, double b) const {
        BzjCurve* out = nullptr;
        check(bzj_curve_segment(handle_, a, b, &out), "bzj_curve_segment");
        return Curve(out);
    }

    /// s -> c(1 - s).
    Curve reverse() const {
        BzjCurve* out = nullptr;
        check(bzj_curve_reverse(handle_, &out), "bzj_curve_reverse");
        return Curve(out);
    }

    /// Signed arc length from parameter a to b.
    double length(double a = 0.0, double b = 1.0) const {
        double out = 0.0;
        check(bzj_curve_length(handle_, a, b, &out), "bzj_curve_length");
        return out;
    }

private:
    BzjCurve* handle_ = nullptr;
};

#if BEZJOIN_HAS_CONNECT
/// R^(k)(t) = values row k, k = 0..max_order, at an interior parameter t.
struct PointConstraint {
    double t = 0.5;
    std::size_t max_order = 0;
    std::vector<double> values;  // (max_order + 1) * dim, row k = R^(k)(t)
};

/// Options of connect(): continuity orders, shape scales, extra constraints.
struct ConnectOptions {
    std::size_t p_order = 0;  // kp <= degree of P
    std::size_t q_order = 0;  // kq <= degree of Q
    double p_scale = 1.0;     // alpha > 0; 1.0 = the paper
    double q_scale = 1.0;     // beta > 0; 1.0 = the paper
    std::vector<PointConstraint> constraints;
};

/// The connecting curve R with R^(k)(0) = alpha^k P^(k)(u0), k <= kp, and
/// R^(k)(1) = beta^k Q^(k)(v0), k <= kq (mathematics.md section 1).
inline Curve connect(const Curve& p, double u0, const Curve& q, double v0,
                     const ConnectOptions& options) {
    std::vector<BzjPointConstraint> constraints;
    constraints.reserve(options.constraints.size());
    for (const PointConstraint& c : options.constraints) {
        BzjPointConstraint raw{};
        raw.t = c.t;
        raw.max_order = c.max_order;
        raw.values = c.values.data();
        constraints.push_back(raw);
    }
    BzjConnectOptions raw{};
    raw.p_order = options.p_order;
    raw.q_order = options.q_order;
    raw.p_scale = options.p_scale;
    raw.q_scale = options.q_scale;
    raw.constraints = constraints.empty() ? nullptr : constraints.data();
    raw.constraint_count = constraints.size();
    BzjCurve* out = nullptr;
    check(bzj_connect(p.get(), u0, q.get(), v0, &raw, &out), "bzj_connect");
    return Curve(out);
}
#endif  // BEZJOIN_HAS_CONNECT

#if BEZJOIN_HAS_FILLET
/// Options of fillet(): arc-length setbacks from the crossing, orders, scales.
struct FilletOptions {
    double p_setback = 0.0;  // arc length along P back from the crossing, > 0
    double q_setback = 0.0;  // arc length along Q on from the crossing, > 0
    std::size_t p_order = 0;
    std::size_t q_order = 0;
    double p_scale = 1.0;
    double q_scale = 1.0;
};

/// The three curves of a rounded corner: P on [0, u0], the blend, Q on [v0, 1].
struct Fillet {
    Curve p_trimmed;
    Curve blend;
    Curve q_trimmed;
};

/// Round the corner at the first crossing of P and Q (mathematics.md section 2).
inline Fillet fillet(const Curve& p, const Curve& q, const FilletOptions& options) {
    BzjFilletOptions raw{};
    raw.p_setback = options.p_setback;
    raw.q_setback = options.q_setback;
    raw.p_order = options.p_order;
    raw.q_order = options.q_order;
    raw.p_scale = options.p_scale;
    raw.q_scale = options.q_scale;
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    check(bzj_fillet(p.get(), q.get(), &raw, &p_trimmed, &blend, &q_trimmed), "bzj_fillet");
    return Fillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed)};
}

/// All crossings of P and Q, ordered by u: pairs (u on P, v on Q).
inline std::vector<std::pair<double, double>> intersect(const Curve& p, const Curve& q) {
    std::size_t count = 0;
    std::vector<double> buffer(2 * 16);
    check(bzj_intersect(p.get(), q.get(), buffer.data(), buffer.size() / 2, &count),
          "bzj_intersect");
    if (count > buffer.size() / 2) {
        buffer.assign(2 * count, 0.0);
        check(bzj_intersect(p.get(), q.get(), buffer.data(), count, &count), "bzj_intersect");
    }
    std::vector<std::pair<double, double>> out;
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        out.emplace_back(buffer[2 * i], buffer[2 * i + 1]);
    }
    return out;
}
#endif  // BEZJOIN_HAS_FILLET

#if BEZJOIN_HAS_MERGE
/// Keep P^(s)(param) (or Q's) unchanged for s = 0..max_order.
struct KeepPoint {
    double param = 0.0;
    std::size_t max_order = 0;
};

/// Options of merge() (mathematics.md section 3).
struct MergeOptions {
    BzjMetric metric = BZJ_METRIC_DISCRETE;
    BzjSplit split = BZJ_SPLIT_HALF;
    double mu = 0.5;  // used when split == BZJ_SPLIT_GIVEN
    bool keep_p = false;
    bool keep_q = false;
    bool fix_ends = false;
    std::vector<KeepPoint> p_points;
    std::vector<KeepPoint> q_points;
};

/// One curve R and its two pieces P^ = R on [0, mu], Q^ = R on [mu, 1], with
/// the report (mu used, metric value, largest distance to P-then-Q).
struct Merge {
    Curve merged;
    Curve p_hat;
    Curve q_hat;
    BzjMergeReport report;
};

inline Merge merge(const Curve& p, const Curve& q, const MergeOptions& options) {
    std::vector<BzjKeepPoint> p_points;
    std::vector<BzjKeepPoint> q_points;
    for (const KeepPoint& k : options.p_points) {
        BzjKeepPoint raw{};
        raw.param = k.param;
        raw.max_order = k.max_order;
        p_points.push_back(raw);
    }
    for (const KeepPoint& k : options.q_points) {
        BzjKeepPoint raw{};
        raw.param = k.param;
        raw.max_order = k.max_order;
        q_points.push_back(raw);
    }
    BzjMergeOptions raw{};
    raw.metric = options.metric;
    raw.split = options.split;
    raw.mu = options.mu;
    raw.keep_p = options.keep_p;
    raw.keep_q = options.keep_q;
    raw.fix_ends = options.fix_ends;
    raw.p_points = p_points.empty() ? nullptr : p_points.data();
    raw.p_point_count = p_points.size();
    raw.q_points = q_points.empty() ? nullptr : q_points.data();
    raw.q_point_count = q_points.size();
    BzjCurve* merged = nullptr;
    BzjCurve* p_hat = nullptr;
    BzjCurve* q_hat = nullptr;
    BzjMergeReport report{};
    check(bzj_merge(p.get(), q.get(), &raw, &merged, &p_hat, &q_hat, &report), "bzj_merge");
    return Merge{Curve(merged), Curve(p_hat), Curve(q_hat), report};
}
#endif  // BEZJOIN_HAS_MERGE

#if BEZJOIN_HAS_LAGRANGE
/// The C1 chain of cubic Bezier segments through `nodes` (node_count * dim)
/// whose inner points at u = 1/3, 2/3 lie on the curve (mathematics.md
/// section 4). `params` has node_count values, or is empty for chord length;
/// `first_inner` holds both inner points of segment 0 (2 * dim);
/// `second_inner` the u = 2/3 point of every later segment ((node_count-2) * dim).
inline std::vector<Curve> lagrange_spline(std::size_t dim, const std::vector<double>& nodes,
                                          const std::vector<double>& params,
                                          const std::vector<double>& first_inner,
                                          const std::vector<double>& second_inner) {
    if (dim == 0 || nodes.size() % dim != 0) {
        throw std::invalid_argument("lagrange_spline: nodes.size() = " +
                                    std::to_string(nodes.size()) +
                                    " is not a multiple of dim = " + std::to_string(dim));
    }
    const std::size_t node_count = nodes.size() / dim;
    const std::size_t segment_count = node_count >= 1 ? node_count - 1 : 0;
    std::vector<BzjCurve*> raw(segment_count, nullptr);
    const BzjStatus status = bzj_lagrange_spline(
        dim, node_count, nodes.data(), params.empty() ? nullptr : params.data(),
        first_inner.data(), second_inner.data(), raw.data(), raw.size());
    std::vector<Curve> out;
    out.reserve(raw.size());
    for (BzjCurve* handle : raw) {
        out.emplace_back(handle);  // owns whatever was written, even on failure
    }
    check(status, "bzj_lagrange_spline");
    return out;
}
#endif  // BEZJOIN_HAS_LAGRANGE

}  // namespace bezjoin

#endif  // BEZJOIN_HPP

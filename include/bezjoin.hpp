// bezjoin.hpp: a small header-only C++17 wrapper over the C ABI in bezjoin.h.
//
// * bezjoin::Curve owns one BzjCurve handle (move-only; released with
//   bzj_curve_free in the destructor): a Bezier curve (parameter in [0, 1]) or
//   a NURBS curve (Curve::nurbs, Curve::ellipse_arc; parameter in its
//   domain(), which the operations keep).
// * Every failed call throws bezjoin::Error, which carries the BzjStatus and the
//   library's message (bzj_last_error(), naming the offending argument).
// * Control points and derivative blocks are row-major std::vector<double>,
//   exactly as in the C contract: point i, coordinate c at [i * dim + c].
//
// Every function of bezjoin.h has a wrapper here (bezjoin_demo in cpp-demo/
// calls each one); option structs mirror the C ones with the C defaults, and
// report structs are the C ones (BzjMergeReport, ...), returned by value.
//
// Contract: shared/spec/c-api.md. Mathematics: shared/spec/mathematics.md.

#ifndef BEZJOIN_HPP
#define BEZJOIN_HPP

#include "bezjoin.h"

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <tuple>
#include <vector>

namespace bezjoin {

/// The name of a status value as the library spells it ("BZJ_ERR_SINGULAR";
/// "BZJ_UNKNOWN_STATUS" for a value that is none) (bzj_status_name).
inline std::string status_name(int32_t status) { return bzj_status_name(status); }

/// The calling thread's message of its last failed call, empty after a
/// success (bzj_last_error). bezjoin::Error carries it already.
inline std::string last_error() { return bzj_last_error(); }

/// A failed bezjoin call: the status code and the library's message.
class Error : public std::runtime_error {
public:
    Error(BzjStatus status, const std::string& operation)
        : std::runtime_error(describe(status, operation)), status_(status) {}

    /// The status the C function returned (never BZJ_OK).
    BzjStatus status() const noexcept { return status_; }

private:
    static std::string describe(BzjStatus status, const std::string& operation) {
        const std::string message = last_error();  // before any other library call
        return operation + ": " + status_name(static_cast<int32_t>(status)) + ": " + message;
    }

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

/// An owning, move-only handle to an immutable curve: a Bezier curve on
/// [0, 1], or a NURBS curve (polynomial or rational, any number of spans) on
/// its domain().
class Curve {
public:
    /// An empty handle (owns nothing).
    Curve() noexcept = default;

    /// Take ownership of a handle returned by the C API (may be NULL).
    explicit Curve(BzjCurve* handle) noexcept : handle_(handle) {}

    /// A Bezier curve of degree `degree` in dimension `dim` from
    /// `(degree + 1) * dim` row-major coordinates.
    Curve(std::size_t dim, std::size_t degree, const std::vector<double>& points) {
        check(bzj_curve_new(dim, degree, points.data(), points.size(), &handle_), "bzj_curve_new");
    }

    /// A NURBS curve of degree `degree >= 1` in dimension `dim`: row-major
    /// poles (`pole_count * dim`, Cartesian), the flat knot vector
    /// (`pole_count + degree + 1` non-decreasing values) and the weights
    /// (`pole_count` values > 0; empty for a polynomial B-spline)
    /// (bzj_nurbs_new).
    static Curve nurbs(std::size_t dim, std::size_t degree, const std::vector<double>& poles,
                       const std::vector<double>& knots,
                       const std::vector<double>& weights = std::vector<double>()) {
        BzjCurve* out = nullptr;
        check(bzj_nurbs_new(dim, degree, poles.data(), poles.size(),
                            weights.empty() ? nullptr : weights.data(), weights.size(),
                            knots.data(), knots.size(), &out),
              "bzj_nurbs_new");
        return Curve(out);
    }

    /// The exact elliptic arc centre + x_radius cos(a) x_axis + y_radius sin(a)
    /// y_axis, a from a0 to a1 (radians, a0 < a1 <= a0 + 2 pi), as a rational
    /// quadratic NURBS curve in dimension 2 or 3 on the domain [a0, a1]; the
    /// axes are orthogonal unit vectors (bzj_nurbs_ellipse_arc). `centre`,
    /// `x_axis`, `y_axis` hold `dim` values each (else std::invalid_argument).
    static Curve ellipse_arc(std::size_t dim, const std::vector<double>& centre,
                             const std::vector<double>& x_axis, const std::vector<double>& y_axis,
                             double x_radius, double y_radius, double a0, double a1) {
        const std::pair<const char*, const std::vector<double>*> vectors[] = {
            {"centre", &centre}, {"x_axis", &x_axis}, {"y_axis", &y_axis}};
        for (const auto& v : vectors) {
            if (v.second->size() != dim) {
                throw std::invalid_argument(std::string("ellipse_arc: ") + v.first + ".size() = " +
                                            std::to_string(v.second->size()) + ", expected dim = " +
                                            std::to_string(dim));
            }
        }
        BzjCurve* out = nullptr;
        check(bzj_nurbs_ellipse_arc(dim, centre.data(), x_axis.data(), y_axis.data(), x_radius,
                                    y_radius, a0, a1, &out),
              "bzj_nurbs_ellipse_arc");
        return Curve(out);
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

    /// The `pole_count() * dim` row-major control points (Bezier: `degree + 1`
    /// of them) or poles (NURBS: Cartesian, not multiplied by the weights).
    std::vector<double> points() const {
        std::vector<double> out(pole_count() * dim());
        check(bzj_curve_points(handle_, out.data(), out.size()), "bzj_curve_points");
        return out;
    }

    /// Whether this is a NURBS curve (false: a Bezier curve) (bzj_curve_is_nurbs).
    bool is_nurbs() const {
        bool out = false;
        check(bzj_curve_is_nurbs(handle_, &out), "bzj_curve_is_nurbs");
        return out;
    }

    /// Whether this is a NURBS curve whose weights are not all equal
    /// (bzj_curve_is_rational).
    bool is_rational() const {
        bool out = false;
        check(bzj_curve_is_rational(handle_, &out), "bzj_curve_is_rational");
        return out;
    }

    /// The number of poles (`degree + 1` for a Bezier curve) (bzj_curve_pole_count).
    std::size_t pole_count() const {
        std::size_t out = 0;
        check(bzj_curve_pole_count(handle_, &out), "bzj_curve_pole_count");
        return out;
    }

    /// The flat knot vector, `pole_count + degree + 1` values (a Bezier curve:
    /// 0 and 1, each `degree + 1` times) (bzj_curve_knots).
    std::vector<double> knots() const {
        std::size_t count = 0;
        check(bzj_curve_knots(handle_, nullptr, 0, &count), "bzj_curve_knots");
        std::vector<double> out(count);
        check(bzj_curve_knots(handle_, out.data(), out.size(), &count), "bzj_curve_knots");
        return out;
    }

    /// The `pole_count` weights, all 1 when the curve is not rational
    /// (bzj_curve_weights).
    std::vector<double> weights() const {
        std::vector<double> out(pole_count());
        check(bzj_curve_weights(handle_, out.data(), out.size()), "bzj_curve_weights");
        return out;
    }

    /// The parameter domain (first, last): (0, 1) for a Bezier curve
    /// (bzj_curve_domain).
    std::pair<double, double> domain() const {
        double first = 0.0;
        double last = 0.0;
        check(bzj_curve_domain(handle_, &first, &last), "bzj_curve_domain");
        return {first, last};
    }

    /// The same curve as a NURBS curve (a Bezier curve: one span on [0, 1], a
    /// point raised to degree 1) (bzj_curve_to_nurbs).
    Curve to_nurbs() const {
        BzjCurve* out = nullptr;
        check(bzj_curve_to_nurbs(handle_, &out), "bzj_curve_to_nurbs");
        return Curve(out);
    }

    /// The Bezier spans in order (bzj_curve_bezier_spans): a polynomial span
    /// as a Bezier curve (the span reparametrised to [0, 1]), a rational span
    /// as a one-span NURBS curve with the original parameters.
    std::vector<Curve> bezier_spans() const {
        std::size_t count = 0;
        check(bzj_curve_bezier_spans(handle_, nullptr, 0, &count), "bzj_curve_bezier_spans");
        std::vector<Curve> out;
        out.reserve(count);
        std::vector<BzjCurve*> raw(count, nullptr);
        const BzjStatus status = bzj_curve_bezier_spans(handle_, raw.data(), raw.size(), &count);
        for (BzjCurve* span : raw) {
            out.emplace_back(span);  // owned even if the call failed (then NULL)
        }
        check(status, "bzj_curve_bezier_spans");
        return out;
    }

    /// Value and derivatives 0..max_order at `t` (any order; a NURBS curve
    /// takes `t` in its domain only): row k (dim doubles) is the k-th
    /// derivative.
    std::vector<double> eval(double t, std::size_t max_order = 0) const {
        std::vector<double> out((max_order + 1) * dim());
        check(bzj_curve_eval(handle_, t, max_order, out.data(), out.size()), "bzj_curve_eval");
        return out;
    }

    /// Value and derivatives 0..max_order at every parameter of `ts` in one
    /// call, parameter-major: `out[(i * (max_order + 1) + k) * dim + c]`.
    std::vector<double> eval_many(const std::vector<double>& ts, std::size_t max_order = 0) const {
        std::vector<double> out(ts.size() * (max_order + 1) * dim());
        check(bzj_curve_eval_many(handle_, ts.data(), ts.size(), max_order, out.data(), out.size()),
              "bzj_curve_eval_many");
        return out;
    }

    /// As eval(), into a caller buffer of `out_len >= (max_order + 1) * dim`
    /// doubles (no allocation; for hot loops).
    void eval_into(double t, std::size_t max_order, double* out, std::size_t out_len) const {
        check(bzj_curve_eval(handle_, t, max_order, out, out_len), "bzj_curve_eval");
    }

    /// The same curve written with degree `new_degree >= degree()` (exact; a
    /// NURBS curve: every span raised, same domain).
    Curve elevate(std::size_t new_degree) const {
        BzjCurve* out = nullptr;
        check(bzj_curve_elevate(handle_, new_degree, &out), "bzj_curve_elevate");
        return Curve(out);
    }

    /// The pieces on [0, t] and [t, 1], each reparametrised to [0, 1]; a NURBS
    /// curve: t inside its domain (first, last), pieces on [first, t] and
    /// [t, last] with the original parameters.
    std::pair<Curve, Curve> split(double t) const {
        BzjCurve* left = nullptr;
        BzjCurve* right = nullptr;
        check(bzj_curve_split(handle_, t, &left, &right), "bzj_curve_split");
        return {Curve(left), Curve(right)};
    }

    /// s -> c(a + (b - a) s), any finite a, b (extrapolation allowed); a NURBS
    /// curve: the piece on [a, b] (first <= a < b <= last) with the original
    /// parameters.
    Curve segment(double a, double b) const {
        BzjCurve* out = nullptr;
        check(bzj_curve_segment(handle_, a, b, &out), "bzj_curve_segment");
        return Curve(out);
    }

    /// s -> c(1 - s); a NURBS curve: u -> c(first + last - u), same domain.
    Curve reverse() const {
        BzjCurve* out = nullptr;
        check(bzj_curve_reverse(handle_, &out), "bzj_curve_reverse");
        return Curve(out);
    }

    /// Signed arc length from parameter a to b (a NURBS curve: both in its
    /// domain).
    double length(double a, double b) const {
        double out = 0.0;
        check(bzj_curve_length(handle_, a, b, &out), "bzj_curve_length");
        return out;
    }

    /// Arc length from parameter a to the end of the domain (1 for a Bezier curve).
    double length(double a) const { return length(a, domain().second); }

    /// Arc length of the whole curve (a Bezier curve: from 0 to 1).
    double length() const {
        const std::pair<double, double> d = domain();
        return length(d.first, d.second);
    }

private:
    BzjCurve* handle_ = nullptr;
};

/// R^(k)(t) = values row k, k = 0..max_order, at an interior parameter t.
struct PointConstraint {
    double t = 0.5;
    std::size_t max_order = 0;
    std::vector<double> values;  // (max_order + 1) * dim, row k = R^(k)(t)
};

/// Options of connect(): continuity orders, shape scales, extra constraints.
struct ConnectOptions {
    std::size_t p_order = 0;  // kp (any order, also above the degree of P)
    std::size_t q_order = 0;  // kq (any order)
    double p_scale = 1.0;     // alpha > 0; 1.0 = the paper
    double q_scale = 1.0;     // beta > 0; 1.0 = the paper
    std::vector<PointConstraint> constraints;
};

namespace detail {

/// The C view of ConnectOptions; points into `options` and into itself, so it
/// is neither copied nor moved (build it in place, pass raw()).
class RawConnectOptions {
public:
    explicit RawConnectOptions(const ConnectOptions& options) {
        constraints_.reserve(options.constraints.size());
        for (const PointConstraint& c : options.constraints) {
            BzjPointConstraint raw{};
            raw.t = c.t;
            raw.max_order = c.max_order;
            raw.values = c.values.data();
            constraints_.push_back(raw);
        }
        raw_.p_order = options.p_order;
        raw_.q_order = options.q_order;
        raw_.p_scale = options.p_scale;
        raw_.q_scale = options.q_scale;
        raw_.constraints = constraints_.empty() ? nullptr : constraints_.data();
        raw_.constraint_count = constraints_.size();
    }
    RawConnectOptions(const RawConnectOptions&) = delete;
    RawConnectOptions& operator=(const RawConnectOptions&) = delete;

    const BzjConnectOptions* raw() const noexcept { return &raw_; }

private:
    std::vector<BzjPointConstraint> constraints_;
    BzjConnectOptions raw_{};
};

/// The C handles of `curves` (borrowed; a null pointer or an empty Curve
/// gives NULL, which the library refuses with BZJ_ERR_NULL_POINTER).
inline std::vector<const BzjCurve*> handles(const std::vector<const Curve*>& curves) {
    std::vector<const BzjCurve*> out;
    out.reserve(curves.size());
    for (const Curve* c : curves) {
        out.push_back(c != nullptr ? c->get() : nullptr);
    }
    return out;
}

/// Adopt every handle of `raw` (NULL ones give empty Curves), then throw if
/// `status` is a failure: nothing the library wrote is leaked either way.
inline std::vector<Curve> adopt_all(const std::vector<BzjCurve*>& raw, BzjStatus status,
                                    const char* operation) {
    std::vector<Curve> out;
    out.reserve(raw.size());
    for (BzjCurve* handle : raw) {
        out.emplace_back(handle);
    }
    check(status, operation);
    return out;
}

}  // namespace detail

/// The connecting curve R (a Bezier curve) with R^(k)(0) = alpha^k P^(k)(u0),
/// k <= kp, and R^(k)(1) = beta^k Q^(k)(v0), k <= kq (mathematics.md section
/// 1). P and Q may be Bezier or NURBS curves; u0, v0 lie in their domains; at
/// a knot P's derivatives are taken from the left, Q's from the right.
inline Curve connect(const Curve& p, double u0, const Curve& q, double v0,
                     const ConnectOptions& options) {
    const detail::RawConnectOptions raw(options);
    BzjCurve* out = nullptr;
    check(bzj_connect(p.get(), u0, q.get(), v0, raw.raw(), &out), "bzj_connect");
    return Curve(out);
}

/// connect() with alpha = beta = scale chosen by the library.
struct AutoScaledConnection {
    Curve curve;
    double scale = 0.0;  // the s = alpha = beta used
};

/// connect() with alpha = beta = s chosen to minimise the fairness energy
/// integral |R''|^2 (bzj_connect_auto_scale); options.p_scale and
/// options.q_scale are ignored.
inline AutoScaledConnection connect_auto_scale(const Curve& p, double u0, const Curve& q, double v0,
                                               const ConnectOptions& options) {
    const detail::RawConnectOptions raw(options);
    BzjCurve* out = nullptr;
    double scale = 0.0;
    check(bzj_connect_auto_scale(p.get(), u0, q.get(), v0, raw.raw(), &out, &scale),
          "bzj_connect_auto_scale");
    return AutoScaledConnection{Curve(out), scale};
}

/// connect() with the blend leaving both curves at one speed sigma.
struct BalancedConnection {
    Curve curve;
    double p_scale = 0.0;  // alpha = sigma / |P'(u0)|
    double q_scale = 0.0;  // beta = sigma / |Q'(v0)|
};

/// connect() with alpha = sigma / |P'(u0)|, beta = sigma / |Q'(v0)|, sigma
/// chosen as connect_auto_scale() chooses s (bzj_connect_balanced_scale): the
/// blend does not depend on how fast P or Q runs in its own parameter.
/// options.p_scale and options.q_scale are ignored.
inline BalancedConnection connect_balanced_scale(const Curve& p, double u0, const Curve& q,
                                                 double v0, const ConnectOptions& options) {
    const detail::RawConnectOptions raw(options);
    BzjCurve* out = nullptr;
    double alpha = 0.0;
    double beta = 0.0;
    check(bzj_connect_balanced_scale(p.get(), u0, q.get(), v0, raw.raw(), &out, &alpha, &beta),
          "bzj_connect_balanced_scale");
    return BalancedConnection{Curve(out), alpha, beta};
}

/// connect() of the Bezier curves with control points `p_points` and
/// `q_points` (row-major, dim coordinates each) without handles
/// (bzj_connect_points): the (p_order + q_order + 2) * dim control points of
/// R, bit for bit those of connect() on Curve(dim, ..., p_points) and
/// Curve(dim, ..., q_points). The points' lengths are checked by the library
/// (a positive multiple of dim).
inline std::vector<double> connect_points(std::size_t dim, const std::vector<double>& p_points,
                                          double u0, const std::vector<double>& q_points, double v0,
                                          std::size_t p_order, std::size_t q_order,
                                          double p_scale = 1.0, double q_scale = 1.0) {
    // A degree above 31 is refused by the library before it writes anything.
    std::vector<double> out(p_order + q_order < 64 ? (p_order + q_order + 2) * dim : 0);
    check(bzj_connect_points(dim, p_points.data(), p_points.size(), u0, q_points.data(),
                             q_points.size(), v0, p_order, q_order, p_scale, q_scale, out.data(),
                             out.size()),
          "bzj_connect_points");
    return out;
}

/// connect_points() with alpha = beta = s chosen as connect_auto_scale()
/// chooses it (bzj_connect_points_auto_scale): R's control points and s.
inline std::pair<std::vector<double>, double> connect_points_auto_scale(
    std::size_t dim, const std::vector<double>& p_points, double u0,
    const std::vector<double>& q_points, double v0, std::size_t p_order, std::size_t q_order) {
    std::vector<double> out(p_order + q_order < 64 ? (p_order + q_order + 2) * dim : 0);
    double scale = 0.0;
    check(bzj_connect_points_auto_scale(dim, p_points.data(), p_points.size(), u0,
                                        q_points.data(), q_points.size(), v0, p_order, q_order,
                                        out.data(), out.size(), &scale),
          "bzj_connect_points_auto_scale");
    return {std::move(out), scale};
}

/// Options of connect_geometric(): G^k orders and, per end, the shape values
/// beta_1 > 0, beta_2, ... (empty: chosen by the library for fairness).
struct GeometricOptions {
    std::size_t p_order = 2;
    std::size_t q_order = 2;
    std::vector<double> p_shape;  // p_order values, or empty
    std::vector<double> q_shape;  // q_order values, or empty
};

/// A G^k connecting curve, the shape values used and its fairness report.
struct GeometricConnection {
    Curve curve;
    std::vector<double> p_shape;
    std::vector<double> q_shape;
    BzjFairnessReport report;
};

/// The Bezier curve meeting P at u0 with G^p_order and Q at v0 with
/// G^q_order (bzj_connect_geometric; mathematics.md section 7). Empty shape
/// vectors leave the choice to the library (minimal fairness energy).
inline GeometricConnection connect_geometric(const Curve& p, double u0, const Curve& q, double v0,
                                             const GeometricOptions& options) {
    for (const auto& [shape, order, name] :
         {std::tuple<const std::vector<double>&, std::size_t, const char*>{
              options.p_shape, options.p_order, "p_shape"},
          std::tuple<const std::vector<double>&, std::size_t, const char*>{
              options.q_shape, options.q_order, "q_shape"}}) {
        if (!shape.empty() && shape.size() != order) {
            throw std::invalid_argument(std::string("connect_geometric: ") + name + " has " +
                                        std::to_string(shape.size()) + " values for order " +
                                        std::to_string(order));
        }
    }
    const BzjGeometricOptions raw{options.p_order, options.q_order,
                                  options.p_shape.empty() ? nullptr : options.p_shape.data(),
                                  options.q_shape.empty() ? nullptr : options.q_shape.data()};
    GeometricConnection result{Curve(nullptr), std::vector<double>(options.p_order),
                               std::vector<double>(options.q_order), BzjFairnessReport{}};
    BzjCurve* out = nullptr;
    check(bzj_connect_geometric(p.get(), u0, q.get(), v0, &raw, &out,
                                result.p_shape.empty() ? nullptr : result.p_shape.data(),
                                result.q_shape.empty() ? nullptr : result.q_shape.data(),
                                &result.report),
          "bzj_connect_geometric");
    result.curve = Curve(out);
    return result;
}

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

namespace detail {

inline BzjFilletOptions raw_fillet_options(const FilletOptions& options) {
    BzjFilletOptions raw{};
    raw.p_setback = options.p_setback;
    raw.q_setback = options.q_setback;
    raw.p_order = options.p_order;
    raw.q_order = options.q_order;
    raw.p_scale = options.p_scale;
    raw.q_scale = options.q_scale;
    return raw;
}

}  // namespace detail

/// Round the corner at the first crossing of P and Q (mathematics.md section 2).
inline Fillet fillet(const Curve& p, const Curve& q, const FilletOptions& options) {
    const BzjFilletOptions raw = detail::raw_fillet_options(options);
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    check(bzj_fillet(p.get(), q.get(), &raw, &p_trimmed, &blend, &q_trimmed), "bzj_fillet");
    return Fillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed)};
}

/// Round the corner at the vertex where P ends and Q starts (a wire's or a
/// sketch's vertex, bzj_fillet_vertex), whatever other crossings P and Q
/// have; P's end and Q's start must lie within `gap` (absolute). NURBS
/// inputs give NURBS pieces with their own parameters.
inline Fillet fillet_vertex(const Curve& p, const Curve& q, const FilletOptions& options,
                            double gap) {
    const BzjFilletOptions raw = detail::raw_fillet_options(options);
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    check(bzj_fillet_vertex(p.get(), q.get(), &raw, gap, &p_trimmed, &blend, &q_trimmed),
          "bzj_fillet_vertex");
    return Fillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed)};
}

/// A corner rounded like the arc of radius `radius`, with a G^order blend.
struct RadiusFillet {
    Curve p_trimmed;
    Curve blend;
    Curve q_trimmed;
    BzjFairnessReport report;
};

/// Round the corner (the shared vertex, else the first crossing) like the
/// circular fillet of `radius`, cut where that arc touches the curves, with
/// a G^order blend of fair shape (bzj_fillet_radius; default G2).
inline RadiusFillet fillet_radius(const Curve& p, const Curve& q, double radius,
                                  std::size_t order = 2) {
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    BzjFairnessReport report{};
    check(bzj_fillet_radius(p.get(), q.get(), radius, order, &p_trimmed, &blend, &q_trimmed,
                            &report),
          "bzj_fillet_radius");
    return RadiusFillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed), report};
}

/// fillet_radius() with more of what the library found: the report (fairness,
/// the blend's largest distance from the arc's circle, the touching points u0
/// on P and v0 on Q) and the arc's centre (dim values).
struct DetailedRadiusFillet {
    Curve p_trimmed;
    Curve blend;
    Curve q_trimmed;
    BzjRadiusFilletReport report;
    std::vector<double> arc_centre;
};

/// fillet_radius() with the arc's centre, the blend's deviation from the arc
/// and the cut parameters (bzj_fillet_radius_detailed; default G2).
inline DetailedRadiusFillet fillet_radius_detailed(const Curve& p, const Curve& q, double radius,
                                                   std::size_t order = 2) {
    // An empty p has no dimension: NULL is passed and the library refuses p by name.
    std::vector<double> centre(p.get() != nullptr ? p.dim() : 0);
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    BzjRadiusFilletReport report{};
    check(bzj_fillet_radius_detailed(p.get(), q.get(), radius, order, &p_trimmed, &blend,
                                     &q_trimmed, &report,
                                     centre.empty() ? nullptr : centre.data()),
          "bzj_fillet_radius_detailed");
    return DetailedRadiusFillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed), report,
                                std::move(centre)};
}

/// fillet() with p_scale = q_scale = scale chosen by the library.
struct AutoScaledFillet {
    Curve p_trimmed;
    Curve blend;
    Curve q_trimmed;
    double scale = 0.0;  // the s = alpha = beta used
};

/// fillet() with alpha = beta = s chosen to minimise the blend's fairness
/// energy (bzj_fillet_auto_scale); options.p_scale and options.q_scale are
/// ignored. The chain has knot intervals (u0, s, 1 - v0).
inline AutoScaledFillet fillet_auto_scale(const Curve& p, const Curve& q,
                                          const FilletOptions& options) {
    const BzjFilletOptions raw = detail::raw_fillet_options(options);
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    double scale = 0.0;
    check(bzj_fillet_auto_scale(p.get(), q.get(), &raw, &p_trimmed, &blend, &q_trimmed, &scale),
          "bzj_fillet_auto_scale");
    return AutoScaledFillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed), scale};
}

/// fillet_vertex() with alpha = beta = s chosen as fillet_auto_scale() chooses
/// it (bzj_fillet_vertex_auto_scale); options.p_scale and options.q_scale are
/// ignored. The default for a caller who gives no scales: the paper's scale 1
/// can loop when the setbacks are short against the curves' parametric speed.
inline AutoScaledFillet fillet_vertex_auto_scale(const Curve& p, const Curve& q,
                                                 const FilletOptions& options, double gap) {
    const BzjFilletOptions raw = detail::raw_fillet_options(options);
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    double scale = 0.0;
    check(bzj_fillet_vertex_auto_scale(p.get(), q.get(), &raw, gap, &p_trimmed, &blend,
                                       &q_trimmed, &scale),
          "bzj_fillet_vertex_auto_scale");
    return AutoScaledFillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed), scale};
}

/// fillet() with the blend leaving both curves at one speed sigma.
struct BalancedFillet {
    Curve p_trimmed;
    Curve blend;
    Curve q_trimmed;
    double p_scale = 0.0;  // alpha = sigma / |P'(u0)|
    double q_scale = 0.0;  // beta = sigma / |Q'(v0)|
};

/// fillet() with alpha = sigma / |P'(u0)|, beta = sigma / |Q'(v0)|, sigma
/// chosen as fillet_auto_scale() chooses s (bzj_fillet_balanced_scale): the
/// blend does not depend on how fast either curve runs in its own parameter.
/// options.p_scale and options.q_scale are ignored.
inline BalancedFillet fillet_balanced_scale(const Curve& p, const Curve& q,
                                            const FilletOptions& options) {
    const BzjFilletOptions raw = detail::raw_fillet_options(options);
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    double alpha = 0.0;
    double beta = 0.0;
    check(bzj_fillet_balanced_scale(p.get(), q.get(), &raw, &p_trimmed, &blend, &q_trimmed,
                                    &alpha, &beta),
          "bzj_fillet_balanced_scale");
    return BalancedFillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed), alpha, beta};
}

/// fillet_vertex() with the scales of fillet_balanced_scale()
/// (bzj_fillet_vertex_balanced_scale): the blend depends on the corner and
/// the setbacks only, not on the edges' lengths or parametrisations.
inline BalancedFillet fillet_vertex_balanced_scale(const Curve& p, const Curve& q,
                                                   const FilletOptions& options, double gap) {
    const BzjFilletOptions raw = detail::raw_fillet_options(options);
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    double alpha = 0.0;
    double beta = 0.0;
    check(bzj_fillet_vertex_balanced_scale(p.get(), q.get(), &raw, gap, &p_trimmed, &blend,
                                           &q_trimmed, &alpha, &beta),
          "bzj_fillet_vertex_balanced_scale");
    return BalancedFillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed), alpha, beta};
}

/// Options of fillet_deviation(): the largest distance of the blend from the
/// corner point, the setback ratio dq / dp, orders, scales.
struct DeviationFilletOptions {
    double max_deviation = 0.0;  // eps > 0
    double setback_ratio = 1.0;  // dq / dp > 0; 1.0 = symmetric
    std::size_t p_order = 0;
    std::size_t q_order = 0;
    double p_scale = 1.0;
    double q_scale = 1.0;
};

/// The rounded corner of fillet_deviation() and what was chosen and achieved
/// (setbacks, deviation, cut parameters u0 and v0).
struct DeviationFillet {
    Curve p_trimmed;
    Curve blend;
    Curve q_trimmed;
    BzjDeviationFilletReport report;
};

namespace detail {
inline BzjDeviationFilletOptions raw_deviation_options(const DeviationFilletOptions& options) {
    BzjDeviationFilletOptions raw{};
    raw.max_deviation = options.max_deviation;
    raw.setback_ratio = options.setback_ratio;
    raw.p_order = options.p_order;
    raw.q_order = options.q_order;
    raw.p_scale = options.p_scale;
    raw.q_scale = options.q_scale;
    return raw;
}
}  // namespace detail

/// Round the corner at the first crossing X so that min over t of |R(t) - X|
/// lies in [eps (1 - 1e-9), eps (1 - 2.5e-10)], never above eps
/// (bzj_fillet_deviation).
inline DeviationFillet fillet_deviation(const Curve& p, const Curve& q,
                                        const DeviationFilletOptions& options) {
    const BzjDeviationFilletOptions raw = detail::raw_deviation_options(options);
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    BzjDeviationFilletReport report{};
    check(bzj_fillet_deviation(p.get(), q.get(), &raw, &p_trimmed, &blend, &q_trimmed, &report),
          "bzj_fillet_deviation");
    return DeviationFillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed), report};
}

/// fillet_deviation() with alpha = beta = s chosen automatically
/// (bzj_fillet_deviation_auto_scale: s is the automatic scale of the very
/// setbacks found with it; options.p_scale and options.q_scale are ignored).
/// The chosen s is returned in `scale`.
inline DeviationFillet fillet_deviation_auto_scale(const Curve& p, const Curve& q,
                                                   const DeviationFilletOptions& options,
                                                   double& scale) {
    const BzjDeviationFilletOptions raw = detail::raw_deviation_options(options);
    BzjCurve* p_trimmed = nullptr;
    BzjCurve* blend = nullptr;
    BzjCurve* q_trimmed = nullptr;
    BzjDeviationFilletReport report{};
    check(bzj_fillet_deviation_auto_scale(p.get(), q.get(), &raw, &p_trimmed, &blend, &q_trimmed,
                                          &report, &scale),
          "bzj_fillet_deviation_auto_scale");
    return DeviationFillet{Curve(p_trimmed), Curve(blend), Curve(q_trimmed), report};
}

/// Round every corner of a chain of curves (corner i between curves[i] and
/// curves[i + 1], and from the last to the first when `closed`) with the same
/// options (bzj_fillet_chain). The pieces in path order: trimmed curve 0,
/// blend 0, trimmed curve 1, ...: 2n - 1 curves (open) or 2n (closed, ending
/// with the blend back to the start).
inline std::vector<Curve> fillet_chain(const std::vector<const Curve*>& curves,
                                       const FilletOptions& options, bool closed = false) {
    const std::vector<const BzjCurve*> handles = detail::handles(curves);
    const BzjFilletOptions raw = detail::raw_fillet_options(options);
    const int32_t closed_flag = closed ? 1 : 0;
    std::size_t count = 0;
    check(bzj_fillet_chain(handles.data(), handles.size(), &raw, closed_flag, nullptr, 0, &count),
          "bzj_fillet_chain");
    std::vector<BzjCurve*> pieces(count, nullptr);
    const BzjStatus status = bzj_fillet_chain(handles.data(), handles.size(), &raw, closed_flag,
                                              pieces.data(), pieces.size(), &count);
    return detail::adopt_all(pieces, status, "bzj_fillet_chain");
}

/// fillet_chain() of curves held in a vector.
inline std::vector<Curve> fillet_chain(const std::vector<Curve>& curves, const FilletOptions& options,
                                       bool closed = false) {
    std::vector<const Curve*> pointers;
    pointers.reserve(curves.size());
    for (const Curve& c : curves) {
        pointers.push_back(&c);
    }
    return fillet_chain(pointers, options, closed);
}

/// fillet_chain({&a, &b, &c}, options): a braced list of curve pointers (this
/// overload keeps the list from reading as a vector<Curve> iterator pair).
inline std::vector<Curve> fillet_chain(std::initializer_list<const Curve*> curves,
                                       const FilletOptions& options, bool closed = false) {
    return fillet_chain(std::vector<const Curve*>(curves), options, closed);
}

namespace detail {

/// The number of corners of a chain of `curve_count` curves.
inline std::size_t corner_count(std::size_t curve_count, bool closed) {
    return closed ? curve_count : (curve_count == 0 ? 0 : curve_count - 1);
}

inline std::vector<const Curve*> pointers(const std::vector<Curve>& curves) {
    std::vector<const Curve*> out;
    out.reserve(curves.size());
    for (const Curve& c : curves) {
        out.push_back(&c);
    }
    return out;
}

}  // namespace detail

/// Every corner of a chain rounded with its own automatic scale.
struct AutoScaledFilletChain {
    std::vector<Curve> pieces;  // path order, as fillet_chain()
    std::vector<double> scales;  // the s of corner i at index i
};

/// fillet_chain() with alpha = beta = s chosen at every corner as
/// fillet_auto_scale() chooses it (bzj_fillet_chain_auto_scale);
/// options.p_scale and options.q_scale are ignored.
inline AutoScaledFilletChain fillet_chain_auto_scale(const std::vector<const Curve*>& curves,
                                                     const FilletOptions& options,
                                                     bool closed = false) {
    const std::vector<const BzjCurve*> handles = detail::handles(curves);
    const BzjFilletOptions raw = detail::raw_fillet_options(options);
    const int32_t closed_flag = closed ? 1 : 0;
    std::size_t count = 0;
    check(bzj_fillet_chain_auto_scale(handles.data(), handles.size(), &raw, closed_flag, nullptr,
                                      0, &count, nullptr),
          "bzj_fillet_chain_auto_scale");
    std::vector<BzjCurve*> pieces(count, nullptr);
    std::vector<double> scales(detail::corner_count(handles.size(), closed));
    const BzjStatus status = bzj_fillet_chain_auto_scale(
        handles.data(), handles.size(), &raw, closed_flag, pieces.data(), pieces.size(), &count,
        scales.empty() ? nullptr : scales.data());
    return AutoScaledFilletChain{detail::adopt_all(pieces, status, "bzj_fillet_chain_auto_scale"),
                                 std::move(scales)};
}

/// fillet_chain_auto_scale() of curves held in a vector.
inline AutoScaledFilletChain fillet_chain_auto_scale(const std::vector<Curve>& curves,
                                                     const FilletOptions& options,
                                                     bool closed = false) {
    return fillet_chain_auto_scale(detail::pointers(curves), options, closed);
}

/// fillet_chain_auto_scale({&a, &b, &c}, options): a braced list of curve pointers.
inline AutoScaledFilletChain fillet_chain_auto_scale(std::initializer_list<const Curve*> curves,
                                                     const FilletOptions& options,
                                                     bool closed = false) {
    return fillet_chain_auto_scale(std::vector<const Curve*>(curves), options, closed);
}

/// fillet_chain() with every corner's blend leaving both its curves at one speed.
struct BalancedFilletChain {
    std::vector<Curve> pieces;  // path order, as fillet_chain()
    std::vector<double> scales;  // alpha, beta of corner i at 2 i, 2 i + 1
};

/// fillet_chain() with the scales of fillet_balanced_scale() at every corner
/// (bzj_fillet_chain_balanced_scale); options.p_scale and options.q_scale are
/// ignored.
inline BalancedFilletChain fillet_chain_balanced_scale(const std::vector<const Curve*>& curves,
                                                       const FilletOptions& options,
                                                       bool closed = false) {
    const std::vector<const BzjCurve*> handles = detail::handles(curves);
    const BzjFilletOptions raw = detail::raw_fillet_options(options);
    const int32_t closed_flag = closed ? 1 : 0;
    std::size_t count = 0;
    check(bzj_fillet_chain_balanced_scale(handles.data(), handles.size(), &raw, closed_flag,
                                          nullptr, 0, &count, nullptr),
          "bzj_fillet_chain_balanced_scale");
    std::vector<BzjCurve*> pieces(count, nullptr);
    std::vector<double> scales(2 * detail::corner_count(handles.size(), closed));
    const BzjStatus status = bzj_fillet_chain_balanced_scale(
        handles.data(), handles.size(), &raw, closed_flag, pieces.data(), pieces.size(), &count,
        scales.empty() ? nullptr : scales.data());
    return BalancedFilletChain{
        detail::adopt_all(pieces, status, "bzj_fillet_chain_balanced_scale"), std::move(scales)};
}

/// fillet_chain_balanced_scale() of curves held in a vector.
inline BalancedFilletChain fillet_chain_balanced_scale(const std::vector<Curve>& curves,
                                                       const FilletOptions& options,
                                                       bool closed = false) {
    return fillet_chain_balanced_scale(detail::pointers(curves), options, closed);
}

/// Every corner of a chain rounded by radius, with one report per corner.
struct RadiusFilletChain {
    std::vector<Curve> pieces;  // path order, as fillet_chain()
    std::vector<BzjRadiusFilletReport> reports;  // corner i at index i
};

/// Round every corner of a chain (a wire) like the G1 arc of `radius` with a
/// fair G^order blend, each as fillet_radius() rounds one: corner i between
/// curves[i] and curves[i + 1] (and from the last to the first when `closed`)
/// is their shared vertex, else their crossing nearest the shared end
/// (bzj_fillet_radius_chain; default G2). Pieces in path order as
/// fillet_chain().
inline RadiusFilletChain fillet_radius_chain(const std::vector<const Curve*>& curves,
                                             double radius, std::size_t order = 2,
                                             bool closed = false) {
    const std::vector<const BzjCurve*> handles = detail::handles(curves);
    const int32_t closed_flag = closed ? 1 : 0;
    std::size_t count = 0;
    check(bzj_fillet_radius_chain(handles.data(), handles.size(), radius, order, closed_flag,
                                  nullptr, 0, &count, nullptr),
          "bzj_fillet_radius_chain");
    std::vector<BzjCurve*> pieces(count, nullptr);
    std::vector<BzjRadiusFilletReport> reports(detail::corner_count(handles.size(), closed));
    const BzjStatus status = bzj_fillet_radius_chain(
        handles.data(), handles.size(), radius, order, closed_flag, pieces.data(), pieces.size(),
        &count, reports.empty() ? nullptr : reports.data());
    return RadiusFilletChain{detail::adopt_all(pieces, status, "bzj_fillet_radius_chain"),
                             std::move(reports)};
}

/// fillet_radius_chain() of curves held in a vector.
inline RadiusFilletChain fillet_radius_chain(const std::vector<Curve>& curves, double radius,
                                             std::size_t order = 2, bool closed = false) {
    return fillet_radius_chain(detail::pointers(curves), radius, order, closed);
}

/// fillet_radius_chain({&a, &b, &c}, radius): a braced list of curve pointers.
inline RadiusFilletChain fillet_radius_chain(std::initializer_list<const Curve*> curves,
                                             double radius, std::size_t order = 2,
                                             bool closed = false) {
    return fillet_radius_chain(std::vector<const Curve*>(curves), radius, order, closed);
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

/// The library's default intersection tolerances and work bounds
/// (bzj_intersect_options_default): change what you need and pass the result
/// to intersect_detailed().
inline BzjIntersectOptions intersect_options_default() {
    BzjIntersectOptions out{};
    check(bzj_intersect_options_default(&out), "bzj_intersect_options_default");
    return out;
}

/// Every place where P and Q meet, ordered by u, with its kind (crossing,
/// touching, overlap with its range) (bzj_intersect_detailed).
inline std::vector<BzjIntersection> intersect_detailed(const Curve& p, const Curve& q,
                                                       const BzjIntersectOptions& options) {
    std::size_t count = 0;
    std::vector<BzjIntersection> out(16);
    check(bzj_intersect_detailed(p.get(), q.get(), &options, out.data(), out.size(), &count),
          "bzj_intersect_detailed");
    if (count > out.size()) {
        out.assign(count, BzjIntersection{});
        check(bzj_intersect_detailed(p.get(), q.get(), &options, out.data(), out.size(), &count),
              "bzj_intersect_detailed");
    }
    out.resize(count);
    return out;
}

/// intersect_detailed() with the default options.
inline std::vector<BzjIntersection> intersect_detailed(const Curve& p, const Curve& q) {
    return intersect_detailed(p, q, intersect_options_default());
}

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
/// the report (mu used, metric value, largest distance to P-then-Q). For
/// B-spline (NURBS) inputs R is a NURBS curve on [0, 1] and P^, Q^ are NURBS
/// curves on P's and Q's own knots and parameters.
struct Merge {
    Curve merged;
    Curve p_hat;
    Curve q_hat;
    BzjMergeReport report;
};

namespace detail {

/// Merge with the library's degree (`degree == 0`) or with `degree`.
inline Merge merge(const Curve& p, const Curve& q, const MergeOptions& options, std::size_t degree) {
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
    if (degree == 0) {
        check(bzj_merge(p.get(), q.get(), &raw, &merged, &p_hat, &q_hat, &report), "bzj_merge");
    } else {
        check(bzj_merge_to_degree(p.get(), q.get(), &raw, degree, &merged, &p_hat, &q_hat, &report),
              "bzj_merge_to_degree");
    }
    return Merge{Curve(merged), Curve(p_hat), Curve(q_hat), report};
}

}  // namespace detail

inline Merge merge(const Curve& p, const Curve& q, const MergeOptions& options) {
    return detail::merge(p, q, options, 0);
}

/// merge() into a curve of degree `degree` (at least both curves' degrees;
/// both are elevated first) (bzj_merge_to_degree).
inline Merge merge_to_degree(const Curve& p, const Curve& q, const MergeOptions& options,
                             std::size_t degree) {
    if (degree == 0) {
        // 0 would select bzj_merge above; the library refuses it as below the degrees.
        throw std::invalid_argument("merge_to_degree: degree = 0 is below the curves' degrees");
    }
    return detail::merge(p, q, options, degree);
}

/// Keep the point of curve `curve` at `param` with derivatives 0..max_order.
struct ChainKeepPoint {
    std::size_t curve = 0;
    double param = 0.0;
    std::size_t max_order = 0;
};

/// Options of merge_chain().
struct ChainMergeOptions {
    BzjMetric metric = BZJ_METRIC_DISCRETE;
    BzjChainSplit split = BZJ_CHAIN_SPLIT_UNIFORM;
    std::vector<double> breakpoints;  // curve count - 1 interior values, for BZJ_CHAIN_SPLIT_GIVEN
    std::size_t degree = 0;           // 0: the highest degree of the curves
    bool fix_ends = false;
    std::vector<bool> keep;           // empty, or one "unchanged" flag per curve
    std::vector<ChainKeepPoint> keep_points;
};

/// One curve R and its pieces (curve j changed into R on [t_j, t_{j+1}]),
/// the breakpoints t_0 = 0 < ... < t_N = 1, and the report.
struct ChainMerge {
    Curve merged;
    std::vector<Curve> pieces;
    std::vector<double> breakpoints;
    BzjChainMergeReport report;
};

/// Merge N >= 2 consecutive curves into one curve (bzj_merge_chain): a Bezier
/// curve for Bezier inputs, a NURBS curve when any input is a B-spline.
inline ChainMerge merge_chain(const std::vector<const Curve*>& curves,
                              const ChainMergeOptions& options) {
    const std::vector<const BzjCurve*> handles = detail::handles(curves);
    if (!options.keep.empty() && options.keep.size() != curves.size()) {
        throw std::invalid_argument("merge_chain: keep has " + std::to_string(options.keep.size()) +
                                    " flags for " + std::to_string(curves.size()) + " curves");
    }
    // std::vector<bool> is not an array of bool.
    std::unique_ptr<bool[]> keep(new bool[options.keep.size() + 1]());
    for (std::size_t i = 0; i < options.keep.size(); ++i) {
        keep[i] = options.keep[i];
    }
    std::vector<BzjChainKeepPoint> keep_points;
    for (const ChainKeepPoint& k : options.keep_points) {
        BzjChainKeepPoint raw{};
        raw.curve = k.curve;
        raw.param = k.param;
        raw.max_order = k.max_order;
        keep_points.push_back(raw);
    }
    BzjChainMergeOptions raw{};
    raw.metric = options.metric;
    raw.split = options.split;
    raw.breakpoints = options.breakpoints.empty() ? nullptr : options.breakpoints.data();
    raw.breakpoint_count = options.breakpoints.size();
    raw.degree = options.degree;
    raw.fix_ends = options.fix_ends;
    raw.keep = options.keep.empty() ? nullptr : keep.get();
    raw.keep_points = keep_points.empty() ? nullptr : keep_points.data();
    raw.keep_point_count = keep_points.size();
    BzjCurve* merged = nullptr;
    std::vector<BzjCurve*> pieces(curves.size(), nullptr);
    std::vector<double> breakpoints(curves.size() + 1, 0.0);
    BzjChainMergeReport report{};
    const BzjStatus status = bzj_merge_chain(
        handles.data(), handles.size(), &raw, &merged, pieces.data(), pieces.size(),
        breakpoints.data(), breakpoints.size(), &report);
    Curve owned(merged);
    std::vector<Curve> owned_pieces = detail::adopt_all(pieces, status, "bzj_merge_chain");
    return ChainMerge{std::move(owned), std::move(owned_pieces), std::move(breakpoints), report};
}

/// merge_chain() of curves held in a vector.
inline ChainMerge merge_chain(const std::vector<Curve>& curves, const ChainMergeOptions& options) {
    std::vector<const Curve*> pointers;
    pointers.reserve(curves.size());
    for (const Curve& c : curves) {
        pointers.push_back(&c);
    }
    return merge_chain(pointers, options);
}

/// merge_chain({&a, &b, &c}, options): a braced list of curve pointers.
inline ChainMerge merge_chain(std::initializer_list<const Curve*> curves,
                              const ChainMergeOptions& options) {
    return merge_chain(std::vector<const Curve*>(curves), options);
}

namespace detail {

/// The number of points in `nodes` (a multiple of `dim`), else std::invalid_argument.
inline std::size_t node_count(const char* operation, std::size_t dim,
                              const std::vector<double>& nodes) {
    if (dim == 0 || nodes.size() % dim != 0) {
        throw std::invalid_argument(std::string(operation) + ": nodes.size() = " +
                                    std::to_string(nodes.size()) +
                                    " is not a multiple of dim = " + std::to_string(dim));
    }
    return nodes.size() / dim;
}

/// The C function reads as many doubles as its counts imply: a shorter (or
/// longer) vector is refused here with std::invalid_argument.
inline void expect_size(const char* operation, const char* name, const std::vector<double>& values,
                        std::size_t wanted) {
    if (values.size() != wanted) {
        throw std::invalid_argument(std::string(operation) + ": " + name + ".size() = " +
                                    std::to_string(values.size()) + ", expected " +
                                    std::to_string(wanted));
    }
}

/// Call a Lagrange spline function writing node_count - 1 handles into a
/// buffer; adopt them (owning whatever was written, even on failure) and check.
template <typename Call>
std::vector<Curve> lagrange_segments(std::size_t node_count, const char* operation, Call&& call) {
    const std::size_t segment_count = node_count >= 1 ? node_count - 1 : 0;
    std::vector<BzjCurve*> raw(segment_count, nullptr);
    const BzjStatus status = call(raw.data(), raw.size());
    return adopt_all(raw, status, operation);
}

}  // namespace detail

/// The C1 chain of cubic Bezier segments through `nodes` (node_count * dim)
/// whose inner points at u = 1/3, 2/3 lie on the curve (mathematics.md
/// section 4). `params` has node_count values, or is empty for chord length;
/// `first_inner` holds both inner points of segment 0 (2 * dim);
/// `second_inner` the u = 2/3 point of every later segment ((node_count-2) * dim).
inline std::vector<Curve> lagrange_spline(std::size_t dim, const std::vector<double>& nodes,
                                          const std::vector<double>& params,
                                          const std::vector<double>& first_inner,
                                          const std::vector<double>& second_inner) {
    const char* operation = "lagrange_spline";
    const std::size_t node_count = detail::node_count(operation, dim, nodes);
    if (node_count >= 2) {  // fewer: the library refuses node_count itself
        detail::expect_size(operation, "first_inner", first_inner, 2 * dim);
        detail::expect_size(operation, "second_inner", second_inner, (node_count - 2) * dim);
        if (!params.empty()) {
            detail::expect_size(operation, "params", params, node_count);
        }
    }
    return detail::lagrange_segments(node_count, "bzj_lagrange_spline", [&](BzjCurve** out,
                                                                             std::size_t capacity) {
        return bzj_lagrange_spline(dim, node_count, nodes.data(),
                                   params.empty() ? nullptr : params.data(), first_inner.data(),
                                   second_inner.empty() ? nullptr : second_inner.data(), out,
                                   capacity);
    });
}

/// The generalisation of lagrange_spline(): segments of degree `degree`
/// (3, 4 or 5) through points on them at u = j / degree, joined
/// C^`continuity` (1 ..= degree - 2) at every node (bzj_lagrange_spline_degree).
/// `flags`: 0 or BZJ_LAGRANGE_BACKWARD | BZJ_LAGRANGE_MIRRORED. `start_inner`:
/// the (degree - 1) inner points of the starting segment; `free_inner`: the
/// (degree - 1 - continuity) free inner points of every other segment, in
/// segment order ((node_count - 2) * (degree - 1 - continuity) * dim doubles).
inline std::vector<Curve> lagrange_spline_degree(std::size_t dim, std::size_t degree,
                                                 std::size_t continuity, uint32_t flags,
                                                 const std::vector<double>& nodes,
                                                 const std::vector<double>& params,
                                                 const std::vector<double>& start_inner,
                                                 const std::vector<double>& free_inner) {
    const char* operation = "lagrange_spline_degree";
    const std::size_t node_count = detail::node_count(operation, dim, nodes);
    // Outside these ranges the library refuses degree, continuity or node_count.
    if (node_count >= 2 && degree >= 3 && degree <= 5 && continuity >= 1 &&
        continuity + 2 <= degree) {
        detail::expect_size(operation, "start_inner", start_inner, (degree - 1) * dim);
        detail::expect_size(operation, "free_inner", free_inner,
                            (node_count - 2) * (degree - 1 - continuity) * dim);
        if (!params.empty()) {
            detail::expect_size(operation, "params", params, node_count);
        }
    }
    return detail::lagrange_segments(
        node_count, "bzj_lagrange_spline_degree", [&](BzjCurve** out, std::size_t capacity) {
            return bzj_lagrange_spline_degree(
                dim, degree, continuity, flags, node_count, nodes.data(),
                params.empty() ? nullptr : params.data(), start_inner.data(),
                free_inner.empty() ? nullptr : free_inner.data(), out, capacity);
        });
}

}  // namespace bezjoin

#endif  // BEZJOIN_HPP

// bezjoin C++ demo: our curves checked by OpenCASCADE's NURBS code, side-by-side
// timings, and a STEP file of the demo's curves.
//
// Every check prints one row "PASS|FAIL name worst-error (tolerance) note";
// the program exits 1 if any row is FAIL. Informational rows start with INFO.
//
// Usage: bezjoin_demo [--quick] [--step FILE] [--leak-on-purpose]
//   --quick            run every code path once instead of timing it (valgrind)
//   --step FILE        where to write the STEP file (default bezjoin-demo.step)
//   --leak-on-purpose  leak one bezjoin curve and exit 0: run.sh uses it to
//                      show that its leak check does catch a leak of ours.

#include "bezjoin.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <BSplCLib.hxx>
#include <ChFi2d_AnaFilletAlgo.hxx>
#include <ChFi2d_FilletAPI.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <Geom2dAPI_InterCurveCurve.hxx>
#include <Geom2dAdaptor_Curve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GC_MakeArcOfEllipse.hxx>
#include <GC_MakeCircle.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomConvert.hxx>
#include <GeomConvert_CompCurveToBSplineCurve.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Line.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <gp_Circ.hxx>
#include <gp_Elips.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <GeomLProp_CLProps.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BezierCurve.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Pln.hxx>
#include <math_Gauss.hxx>
#include <math_Matrix.hxx>
#include <math_Vector.hxx>

#include <Standard_Version.hxx>

#include <algorithm>
#include <array>
#include <cstdarg>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "connect_floor.hpp"

namespace {

using bezjoin::Curve;

// ---------------------------------------------------------------- reporting

struct Report {
    int failures = 0;

    void row(bool pass, const std::string& name, double worst, double tolerance,
             const std::string& note = "", const char* tolerance_suffix = "") {
        if (!pass) {
            ++failures;
        }
        std::printf("%s %-34s %10.3e  (tol %.0e%s)%s%s\n", pass ? "PASS" : "FAIL", name.c_str(), worst,
                    tolerance, tolerance_suffix, note.empty() ? "" : "  ", note.c_str());
        std::fflush(stdout);
    }

    void fail(const std::string& name, const std::string& why) {
        ++failures;
        std::printf("FAIL %-34s %10s  %s\n", name.c_str(), "-", why.c_str());
        std::fflush(stdout);
    }

    void info(const std::string& name, const std::string& text) {
        std::printf("INFO %-34s %s\n", name.c_str(), text.c_str());
        std::fflush(stdout);
    }
};

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
    char buffer[512];
    va_list args;
    va_start(args, fmt);
    std::vsnprintf(buffer, sizeof buffer, fmt, args);
    va_end(args);
    return buffer;
}

// Run one check; an exception (ours or OCCT's) is a FAIL row, not a crash.
void guarded(Report& report, const std::string& name, const std::function<void()>& body) {
    try {
        body();
    } catch (const bezjoin::Error& e) {
        report.fail(name, std::string("bezjoin::Error ") + e.what());
    } catch (const Standard_Failure& e) {
        report.fail(name, std::string("OCCT ") + e.DynamicType()->Name() + ": " +
                              (e.GetMessageString() ? e.GetMessageString() : ""));
    } catch (const std::exception& e) {
        report.fail(name, e.what());
    }
}

// Expect `body` to throw bezjoin::Error with `status`; one row. Run under
// valgrind too, so the error paths are shown not to leak.
void expect_status(Report& report, const std::string& name, BzjStatus status,
                   const std::function<void()>& body) {
    try {
        body();
        report.fail(name, std::string("no error; expected ") + bzj_status_name(status));
    } catch (const bezjoin::Error& e) {
        const bool ok = e.status() == status && std::strlen(e.what()) > 0;
        report.row(ok, name, ok ? 0.0 : 1.0, 0.0, e.what());
    }
}

// ---------------------------------------------------------------- conversions

std::vector<double> random_points(std::mt19937_64& rng, std::size_t dim, std::size_t degree) {
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    std::vector<double> points((degree + 1) * dim);
    for (double& x : points) {
        x = coordinate(rng);
    }
    return points;
}

gp_Pnt point3(const double* p, std::size_t dim) {
    return gp_Pnt(p[0], dim > 1 ? p[1] : 0.0, dim > 2 ? p[2] : 0.0);
}

TColgp_Array1OfPnt poles3(const std::vector<double>& points, std::size_t dim) {
    const int count = static_cast<int>(points.size() / dim);
    TColgp_Array1OfPnt poles(1, count);
    for (int i = 0; i < count; ++i) {
        poles(i + 1) = point3(&points[i * dim], dim);
    }
    return poles;
}

// OCCT's Bezier curve of ours (2D curves lifted to z = 0).
Handle(Geom_BezierCurve) occ_bezier(const Curve& c) {
    return new Geom_BezierCurve(poles3(c.points(), c.dim()));
}

Handle(Geom2d_BezierCurve) occ_bezier2d(const Curve& c) {
    const std::vector<double> points = c.points();
    const int count = static_cast<int>(points.size() / 2);
    TColgp_Array1OfPnt2d poles(1, count);
    for (int i = 0; i < count; ++i) {
        poles(i + 1) = gp_Pnt2d(points[2 * i], points[2 * i + 1]);
    }
    return new Geom2d_BezierCurve(poles);
}

[[maybe_unused]] double max_abs(const std::vector<double>& v) {
    double m = 0.0;
    for (double x : v) {
        m = std::max(m, std::abs(x));
    }
    return m;
}

// Largest coordinate difference between two lists of control points,
// relative to the reference's size (max |coordinate|, at least 1); infinite
// when their lengths differ.
double relative_gap(const std::vector<double>& ours, const std::vector<double>& reference) {
    double gap = ours.size() == reference.size() ? 0.0 : INFINITY;
    for (std::size_t i = 0; i < std::min(ours.size(), reference.size()); ++i) {
        gap = std::max(gap, std::abs(ours[i] - reference[i]));
    }
    return gap / std::max(1.0, max_abs(reference));
}

// Largest coordinate difference between our control points and OCCT's poles,
// relative to the size of the OCCT curve (max |coordinate|, at least 1).
double pole_difference(const Curve& ours, const Handle(Geom_BezierCurve)& occ) {
    const std::vector<double> points = ours.points();
    const std::size_t dim = ours.dim();
    if (static_cast<int>(points.size() / dim) != occ->NbPoles()) {
        return INFINITY;
    }
    double scale = 1.0;
    double worst = 0.0;
    for (int i = 1; i <= occ->NbPoles(); ++i) {
        const gp_Pnt pole = occ->Pole(i);
        for (std::size_t c = 0; c < dim; ++c) {
            scale = std::max(scale, std::abs(pole.Coord(static_cast<int>(c) + 1)));
            worst = std::max(worst, std::abs(points[(i - 1) * dim + c] -
                                             pole.Coord(static_cast<int>(c) + 1)));
        }
    }
    return worst / scale;
}

Handle(Geom_BezierCurve) occ_segment(const Handle(Geom_BezierCurve)& c, double a, double b) {
    Handle(Geom_BezierCurve) copy = Handle(Geom_BezierCurve)::DownCast(c->Copy());
    copy->Segment(a, b);
    return copy;
}

double norm(const gp_Vec& v) { return v.Magnitude(); }

[[maybe_unused]] double curvature(const Handle(Geom_Curve)& c, double u) {
    GeomLProp_CLProps props(c, u, 2, 1e-12);
    return props.Curvature();
}

// Curvature of our curve at t, from our own derivatives (any dim 2 or 3).
[[maybe_unused]] double curvature(const Curve& c, double t) {
    const std::vector<double> d = c.eval(t, 2);
    const std::size_t dim = c.dim();
    const gp_Vec d1(dim > 0 ? d[dim] : 0.0, dim > 1 ? d[dim + 1] : 0.0, dim > 2 ? d[dim + 2] : 0.0);
    const gp_Vec d2(d[2 * dim], dim > 1 ? d[2 * dim + 1] : 0.0, dim > 2 ? d[2 * dim + 2] : 0.0);
    const double speed = d1.Magnitude();
    return d1.Crossed(d2).Magnitude() / (speed * speed * speed);
}

// ---------------------------------------------------------------- chains

// One Geom_BSplineCurve from Bezier pieces on consecutive knot intervals of the
// given lengths (all pieces elevated to the largest degree). Interior knots get
// multiplicity = degree, so neighbours share one pole: the left piece's last
// pole is kept, and `pole_gap` receives the largest distance between it and the
// right piece's first pole (the C^0 defect, relative to the curve's size).
struct Chain {
    Handle(Geom_BSplineCurve) curve;
    std::vector<double> knots;  // distinct knots
    int degree = 0;
    double pole_gap = 0.0;
    double size = 1.0;  // max |coordinate|, at least 1
};

[[maybe_unused]] Chain make_chain(const std::vector<const Curve*>& pieces, const std::vector<double>& intervals,
                 double start = 0.0) {
    Chain chain;
    std::size_t degree = 0;
    for (const Curve* piece : pieces) {
        degree = std::max(degree, piece->degree());
    }
    chain.degree = static_cast<int>(degree);
    const std::size_t dim = pieces.front()->dim();
    std::vector<gp_Pnt> poles;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
        const Curve elevated = pieces[p]->elevate(degree);
        const std::vector<double> points = elevated.points();
        for (std::size_t i = 0; i <= degree; ++i) {
            const gp_Pnt pole = point3(&points[i * dim], dim);
            chain.size = std::max({chain.size, std::abs(pole.X()), std::abs(pole.Y()),
                                   std::abs(pole.Z())});
            if (p > 0 && i == 0) {
                chain.pole_gap = std::max(chain.pole_gap, pole.Distance(poles.back()));
                continue;
            }
            poles.push_back(pole);
        }
    }
    chain.pole_gap /= chain.size;
    const int knot_count = static_cast<int>(pieces.size()) + 1;
    TColStd_Array1OfReal knots(1, knot_count);
    TColStd_Array1OfInteger mults(1, knot_count);
    double x = start;
    chain.knots.push_back(x);
    knots(1) = x;
    mults(1) = chain.degree + 1;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
        x += intervals[p];
        chain.knots.push_back(x);
        knots(static_cast<int>(p) + 2) = x;
        mults(static_cast<int>(p) + 2) = p + 1 == pieces.size() ? chain.degree + 1 : chain.degree;
    }
    TColgp_Array1OfPnt occ_poles(1, static_cast<int>(poles.size()));
    for (std::size_t i = 0; i < poles.size(); ++i) {
        occ_poles(static_cast<int>(i) + 1) = poles[i];
    }
    chain.curve = new Geom_BSplineCurve(occ_poles, knots, mults, chain.degree);
    return chain;
}

// OCCT's verdict on the join at (1-based) knot `index`: RemoveKnot can lower
// the multiplicity to degree - k within `tolerance` (C^k), and the derivatives
// 0..k evaluated from the left span and the right span agree. Returns the worst
// relative derivative jump; `removable` is RemoveKnot's answer; `stricter`
// tells whether it could go one further (C^(k+1); false for a generic join).
struct JoinVerdict {
    bool removable = false;
    bool stricter = false;
    double jump = 0.0;
};

[[maybe_unused]] JoinVerdict judge_join(const Chain& chain, int index, int k, double tolerance) {
    JoinVerdict verdict;
    {
        Handle(Geom_BSplineCurve) copy = Handle(Geom_BSplineCurve)::DownCast(chain.curve->Copy());
        verdict.removable = copy->RemoveKnot(index, chain.degree - k, tolerance);
    }
    if (chain.degree - k - 1 >= 0) {
        Handle(Geom_BSplineCurve) copy = Handle(Geom_BSplineCurve)::DownCast(chain.curve->Copy());
        verdict.stricter = copy->RemoveKnot(index, chain.degree - k - 1, tolerance);
    }
    const double u = chain.knots[index - 1];
    for (int order = 0; order <= k; ++order) {
        gp_Vec left;
        gp_Vec right;
        if (order == 0) {
            left = gp_Vec(chain.curve->LocalValue(u, index - 1, index).XYZ());
            right = gp_Vec(chain.curve->LocalValue(u, index, index + 1).XYZ());
        } else {
            left = chain.curve->LocalDN(u, index - 1, index, order);
            right = chain.curve->LocalDN(u, index, index + 1, order);
        }
        const double scale = std::max({1.0, norm(left), norm(right)});
        verdict.jump = std::max(verdict.jump, (left - right).Magnitude() / scale);
    }
    return verdict;
}

// ---------------------------------------------------------------- timing

using Clock = std::chrono::steady_clock;

// Median over `batches` of the time per call of `body` (called `calls` times per
// batch), in nanoseconds.
template <class Body>
double time_per_call_ns(int batches, int calls, Body&& body) {
    std::vector<double> samples;
    for (int b = 0; b < batches; ++b) {
        const auto start = Clock::now();
        for (int i = 0; i < calls; ++i) {
            body(i);
        }
        const auto stop = Clock::now();
        samples.push_back(std::chrono::duration<double, std::nano>(stop - start).count() / calls);
    }
    std::sort(samples.begin(), samples.end());
    return samples[samples.size() / 2];
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// Ours and OCCT timed in alternating batches (the machine is shared and its
// load drifts; alternating puts both under the same load). Medians of the
// per-call times and of the per-batch ratios OCCT / ours.
struct Pair {
    double ours_ns;
    double occt_ns;
    double ratio;
};

template <class Ours, class Occt>
Pair time_pair(int batches, int ours_calls, Ours&& ours, int occt_calls, Occt&& occt) {
    std::vector<double> a;
    std::vector<double> b;
    std::vector<double> r;
    for (int i = 0; i < batches; ++i) {
        a.push_back(time_per_call_ns(1, ours_calls, ours));
        b.push_back(time_per_call_ns(1, occt_calls, occt));
        r.push_back(b.back() / a.back());
    }
    return {median(a), median(b), median(r)};
}

volatile double g_sink = 0.0;  // keeps timed results alive

std::string format_time(double ns) {
    if (ns >= 1e6) {
        return format("%.2f ms", ns / 1e6);
    }
    if (ns >= 1e3) {
        return format("%.2f us", ns / 1e3);
    }
    return format("%.1f ns", ns);
}

struct Timing {
    std::string name;
    std::string ours_label;
    std::string occt_label;
    Pair pair;
};

// ---------------------------------------------------------------- STEP

struct StepScene {
    BRep_Builder builder;
    TopoDS_Compound compound;
    int edges = 0;

    StepScene() { builder.MakeCompound(compound); }

    void add(const Handle(Geom_Curve)& curve, const gp_Vec& offset) {
        Handle(Geom_Curve) moved = Handle(Geom_Curve)::DownCast(curve->Translated(offset));
        builder.Add(compound, BRepBuilderAPI_MakeEdge(moved).Edge());
        ++edges;
    }
    void add(const Curve& c, const gp_Vec& offset) { add(occ_bezier(c), offset); }
    void add(const TopoDS_Edge& edge, const gp_Vec& offset) {
        double first = 0.0;
        double last = 0.0;
        Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, first, last);
        Handle(Geom_Curve) moved = Handle(Geom_Curve)::DownCast(curve->Translated(offset));
        builder.Add(compound, BRepBuilderAPI_MakeEdge(moved, first, last).Edge());
        ++edges;
    }
};

// ---------------------------------------------------------------- reference

// An independent long-double reference (64-bit mantissa: about 2000 times
// finer than double), used to tell whose rounding a disagreement is.
using Wide = long double;

// C^(k)(t) of the Bezier curve `points` (dim, degree) by forward differences
// and de Casteljau, all in long double.
std::vector<Wide> reference_derivative(const std::vector<double>& points, std::size_t dim,
                                       std::size_t degree, double t, std::size_t k) {
    std::vector<Wide> w(points.begin(), points.end());
    std::size_t n = degree;
    Wide factor = 1.0L;
    for (std::size_t step = 0; step < k; ++step) {
        for (std::size_t i = 0; i + 1 <= n; ++i) {
            for (std::size_t c = 0; c < dim; ++c) {
                w[i * dim + c] = w[(i + 1) * dim + c] - w[i * dim + c];
            }
        }
        factor *= static_cast<Wide>(n);
        --n;
    }
    const Wide x = t;
    for (std::size_t level = 1; level <= n; ++level) {
        for (std::size_t i = 0; i + level <= n; ++i) {
            for (std::size_t c = 0; c < dim; ++c) {
                w[i * dim + c] = (1.0L - x) * w[i * dim + c] + x * w[(i + 1) * dim + c];
            }
        }
    }
    std::vector<Wide> out(dim);
    for (std::size_t c = 0; c < dim; ++c) {
        out[c] = factor * w[c];
    }
    return out;
}

// Control points of s -> C(a + (b - a) s) by blossoming in long double:
// point i = blossom(a^(n-i), b^i).
std::vector<Wide> reference_segment(const std::vector<double>& points, std::size_t dim,
                                    std::size_t degree, double a, double b) {
    std::vector<Wide> out((degree + 1) * dim);
    for (std::size_t i = 0; i <= degree; ++i) {
        std::vector<Wide> w(points.begin(), points.end());
        for (std::size_t level = 1; level <= degree; ++level) {
            const Wide x = level <= degree - i ? static_cast<Wide>(a) : static_cast<Wide>(b);
            for (std::size_t j = 0; j + level <= degree; ++j) {
                for (std::size_t c = 0; c < dim; ++c) {
                    w[j * dim + c] = (1.0L - x) * w[j * dim + c] + x * w[(j + 1) * dim + c];
                }
            }
        }
        for (std::size_t c = 0; c < dim; ++c) {
            out[i * dim + c] = w[c];
        }
    }
    return out;
}

// ---------------------------------------------------------------- the demo

struct Options {
    bool quick = false;
    std::string step_path = "bezjoin-demo.step";
};

// a. values and derivatives vs Geom_BezierCurve::DN / Geom2d_BezierCurve::DN,
// with a long-double reference to say whose rounding any disagreement is.
// Errors of C^(k) are relative to max |C^(k)| over the 101 parameters.
// PASS: ours is within `tolerance` of the reference, and ours vs OCCT is within
// `tolerance` plus OCCT's own distance from the reference.
void check_values_and_derivatives(Report& report, std::mt19937_64& rng) {
    const double tolerance = 1e-12;
    for (std::size_t dim : {2u, 3u}) {
        const std::string name = format("a.values+derivatives-%zud", dim);
        guarded(report, name, [&] {
            double worst = 0.0;         // ours vs OCCT
            double worst_ours = 0.0;    // ours vs reference
            double worst_occt = 0.0;    // OCCT vs reference
            std::size_t agree_up_to = 20;  // highest degree with ours vs OCCT <= tolerance throughout
            bool pass = true;
            for (std::size_t degree = 1; degree <= 20; ++degree) {
                const std::vector<double> points = random_points(rng, dim, degree);
                const Curve curve(dim, degree, points);
                const Handle(Geom_BezierCurve) occ3 = occ_bezier(curve);
                const Handle(Geom2d_BezierCurve) occ2 = dim == 2 ? occ_bezier2d(curve) : nullptr;
                std::vector<std::vector<double>> ours(101);
                std::vector<std::vector<double>> theirs(101);
                std::vector<std::vector<Wide>> exact(101);
                for (int i = 0; i <= 100; ++i) {
                    const double t = i / 100.0;
                    ours[i] = curve.eval(t, degree);
                    theirs[i].resize((degree + 1) * dim);
                    exact[i].resize((degree + 1) * dim);
                    for (std::size_t k = 0; k <= degree; ++k) {
                        double* row = &theirs[i][k * dim];
                        if (dim == 2) {
                            const gp_Vec2d v = k == 0 ? gp_Vec2d(occ2->Value(t).XY())
                                                      : occ2->DN(t, static_cast<int>(k));
                            row[0] = v.X();
                            row[1] = v.Y();
                        } else {
                            const gp_Vec v = k == 0 ? gp_Vec(occ3->Value(t).XYZ())
                                                    : occ3->DN(t, static_cast<int>(k));
                            row[0] = v.X();
                            row[1] = v.Y();
                            row[2] = v.Z();
                        }
                        const std::vector<Wide> r = reference_derivative(points, dim, degree, t, k);
                        std::copy(r.begin(), r.end(), exact[i].begin() + static_cast<long>(k * dim));
                    }
                }
                for (std::size_t k = 0; k <= degree; ++k) {
                    Wide scale = 0.0L;
                    Wide ours_occt = 0.0L;
                    Wide ours_ref = 0.0L;
                    Wide occt_ref = 0.0L;
                    for (int i = 0; i <= 100; ++i) {
                        Wide size = 0.0L, a = 0.0L, b = 0.0L, c2 = 0.0L;
                        for (std::size_t c = 0; c < dim; ++c) {
                            const std::size_t j = k * dim + c;
                            size += exact[i][j] * exact[i][j];
                            a += (ours[i][j] - static_cast<Wide>(theirs[i][j])) * (ours[i][j] - static_cast<Wide>(theirs[i][j]));
                            b += (ours[i][j] - exact[i][j]) * (ours[i][j] - exact[i][j]);
                            c2 += (theirs[i][j] - exact[i][j]) * (theirs[i][j] - exact[i][j]);
                        }
                        scale = std::max(scale, std::sqrt(size));
                        ours_occt = std::max(ours_occt, std::sqrt(a));
                        ours_ref = std::max(ours_ref, std::sqrt(b));
                        occt_ref = std::max(occt_ref, std::sqrt(c2));
                    }
                    const double denominator = static_cast<double>(std::max(scale, 1e-300L));
                    const double e_ours_occt = static_cast<double>(ours_occt) / denominator;
                    const double e_ours_ref = static_cast<double>(ours_ref) / denominator;
                    const double e_occt_ref = static_cast<double>(occt_ref) / denominator;
                    worst = std::max(worst, e_ours_occt);
                    worst_ours = std::max(worst_ours, e_ours_ref);
                    worst_occt = std::max(worst_occt, e_occt_ref);
                    if (e_ours_occt > tolerance && agree_up_to >= degree) {
                        agree_up_to = degree - 1;
                    }
                    pass = pass && e_ours_ref <= tolerance && e_ours_occt <= tolerance + e_occt_ref;
                }
            }
            report.row(pass, name, worst, tolerance,
                       format("ours vs OCCT, degrees 1..20, orders 0..degree, 101 t; within tol up to "
                              "degree %zu; vs long-double reference: ours %.1e, OCCT %.1e",
                              agree_up_to, worst_ours, worst_occt),
                       " + OCCT's own error");
        });
    }
}

// b. elevation vs Increase; split and segment vs Segment; reverse vs Reverse.
void check_exact_operations(Report& report, std::mt19937_64& rng) {
    const double tolerance = 1e-12;
    double worst_elevate = 0.0;
    double worst_reverse = 0.0;
    guarded(report, "b.elevate-vs-Increase", [&] {
        for (std::size_t dim : {2u, 3u}) {
            for (std::size_t degree = 1; degree <= 20; ++degree) {
                const Curve curve(dim, degree, random_points(rng, dim, degree));
                const Handle(Geom_BezierCurve) occ = occ_bezier(curve);
                for (std::size_t target : {degree + 1, degree + 3, std::size_t(25)}) {
                    Handle(Geom_BezierCurve) raised = Handle(Geom_BezierCurve)::DownCast(occ->Copy());
                    raised->Increase(static_cast<int>(target));
                    worst_elevate = std::max(worst_elevate, pole_difference(curve.elevate(target), raised));
                }
            }
        }
        report.row(worst_elevate <= tolerance, "b.elevate-vs-Increase", worst_elevate, tolerance,
                   "degrees 1..20 -> +1, +3, 25; 2D and 3D; control points");
    });
    // Split and segment: ours and OCCT's Segment, each also against the
    // long-double blossom, so a disagreement is attributed (as in a).
    struct Errors {
        double ours_occt = 0.0;
        double ours_ref = 0.0;
        double occt_ref = 0.0;
        std::size_t agree_up_to = 20;
        bool pass = true;
    };
    auto compare = [&](Errors& e, const Curve& ours, const Handle(Geom_BezierCurve)& occ,
                       const std::vector<double>& points, std::size_t dim, std::size_t degree,
                       double a, double b) {
        const std::vector<Wide> exact = reference_segment(points, dim, degree, a, b);
        const std::vector<double> mine = ours.points();
        Wide scale = 1.0L;
        Wide d_ours = 0.0L;
        Wide d_occt = 0.0L;
        for (std::size_t i = 0; i < exact.size(); ++i) {
            scale = std::max(scale, std::abs(exact[i]));
            const Wide theirs = occ->Pole(static_cast<int>(i / dim) + 1).Coord(static_cast<int>(i % dim) + 1);
            d_ours = std::max(d_ours, std::abs(mine[i] - exact[i]));
            d_occt = std::max(d_occt, std::abs(theirs - exact[i]));
        }
        const double ours_occt = pole_difference(ours, occ);
        const double ours_ref = static_cast<double>(d_ours / scale);
        const double occt_ref = static_cast<double>(d_occt / scale);
        e.ours_occt = std::max(e.ours_occt, ours_occt);
        e.ours_ref = std::max(e.ours_ref, ours_ref);
        e.occt_ref = std::max(e.occt_ref, occt_ref);
        if (ours_occt > tolerance && e.agree_up_to >= degree) {
            e.agree_up_to = degree - 1;
        }
        e.pass = e.pass && ours_ref <= tolerance && ours_occt <= tolerance + occt_ref;
    };
    auto note = [](const Errors& e, const char* what) {
        return format("%s; ours vs OCCT within tol up to degree %zu; vs long-double blossom: ours "
                      "%.1e, OCCT %.1e",
                      what, e.agree_up_to, e.ours_ref, e.occt_ref);
    };
    guarded(report, "b.split-vs-Segment", [&] {
        Errors e;
        for (std::size_t degree = 1; degree <= 20; ++degree) {
            for (std::size_t dim : {2u, 3u}) {
                const std::vector<double> points = random_points(rng, dim, degree);
                const Curve curve(dim, degree, points);
                const Handle(Geom_BezierCurve) occ = occ_bezier(curve);
                for (double t : {0.1, 0.37, 0.5, 0.9}) {
                    const auto pieces = curve.split(t);
                    compare(e, pieces.first, occ_segment(occ, 0.0, t), points, dim, degree, 0.0, t);
                    compare(e, pieces.second, occ_segment(occ, t, 1.0), points, dim, degree, t, 1.0);
                }
            }
        }
        report.row(e.pass, "b.split-vs-Segment", e.ours_occt, tolerance,
                   note(e, "t = 0.1 0.37 0.5 0.9, degrees 1..20"), " + OCCT's own error");
    });
    guarded(report, "b.segment-vs-Segment", [&] {
        Errors e;
        for (std::size_t degree = 1; degree <= 20; ++degree) {
            for (std::size_t dim : {2u, 3u}) {
                const std::vector<double> points = random_points(rng, dim, degree);
                const Curve curve(dim, degree, points);
                const Handle(Geom_BezierCurve) occ = occ_bezier(curve);
                const double ranges[][2] = {{0.2, 0.7}, {0.05, 0.95}, {-0.5, 1.5}, {0.3, 1.2}};
                for (const auto& range : ranges) {
                    compare(e, curve.segment(range[0], range[1]), occ_segment(occ, range[0], range[1]),
                            points, dim, degree, range[0], range[1]);
                }
                Handle(Geom_BezierCurve) reversed = Handle(Geom_BezierCurve)::DownCast(occ->Copy());
                reversed->Reverse();
                worst_reverse = std::max(worst_reverse, pole_difference(curve.reverse(), reversed));
            }
        }
        report.row(e.pass, "b.segment-vs-Segment", e.ours_occt, tolerance,
                   note(e, "[0.2,0.7] [0.05,0.95] [-0.5,1.5] [0.3,1.2]"), " + OCCT's own error");
        report.row(worst_reverse <= tolerance, "b.reverse-vs-Reverse", worst_reverse, tolerance,
                   "degrees 1..20, 2D and 3D");
    });
}

// The wrapper turns a failed call into bezjoin::Error with status and message.
void check_error_path(Report& report) {
    guarded(report, "wrapper.error-carries-status", [&] {
        try {
            const Curve bad(2, 3, std::vector<double>(7, 0.0));  // needs 8 doubles
            report.fail("wrapper.error-carries-status", "no exception for points_len = 7");
        } catch (const bezjoin::Error& e) {
            const bool ok = e.status() == BZJ_ERR_INVALID_ARGUMENT &&
                            std::strstr(e.what(), "points") != nullptr;
            report.row(ok, "wrapper.error-carries-status", ok ? 0.0 : 1.0, 0.0, e.what());
        }
        try {
            const Curve nan(2, 1, {0.0, 0.0, NAN, 1.0});
            report.fail("wrapper.error-non-finite", "no exception for NaN");
        } catch (const bezjoin::Error& e) {
            const bool ok = e.status() == BZJ_ERR_NON_FINITE;
            report.row(ok, "wrapper.error-non-finite", ok ? 0.0 : 1.0, 0.0, e.what());
        }
        Curve moved_from(2, 1, {0.0, 0.0, 1.0, 1.0});
        Curve moved_to = std::move(moved_from);
        const bool ok = !moved_from && moved_to && moved_to.degree() == 1;  // NOLINT(bugprone-use-after-move)
        report.row(ok, "wrapper.move-transfers-ownership", ok ? 0.0 : 1.0, 0.0);
    });
}

// bzj_curve_eval_many against OCCT's D0 and D2 at the same parameters (1e-12
// relative), and each block against bzj_curve_eval's (the same bits).
void check_eval_many(Report& report, const Curve& curve, const Handle(Geom_BezierCurve)& occ,
                     const std::vector<double>& params, std::size_t count, std::size_t degree) {
    const std::string name = format("b.eval_many-vs-D0-D2[deg %zu]", degree);
    guarded(report, name, [&] {
        const std::vector<double> ts(params.begin(), params.begin() + static_cast<long>(count));
        const std::vector<double> values = curve.eval_many(ts, 0);
        const std::vector<double> jets = curve.eval_many(ts, 2);
        double worst = 0.0;
        std::size_t same_bits = 0;
        gp_Pnt p;
        gp_Vec d1;
        gp_Vec d2;
        for (std::size_t i = 0; i < count; ++i) {
            occ->D2(ts[i], p, d1, d2);
            const gp_XYZ occt[3] = {p.XYZ(), d1.XYZ(), d2.XYZ()};
            for (int k = 0; k < 3; ++k) {
                const double scale = std::max(1.0, occt[k].Modulus());
                const double* ours = &jets[(i * 3 + k) * 3];
                const gp_XYZ gap = gp_XYZ(ours[0], ours[1], ours[2]) - occt[k];
                worst = std::max(worst, gap.Modulus() / scale);
            }
            const gp_XYZ value(values[i * 3], values[i * 3 + 1], values[i * 3 + 2]);
            worst = std::max(worst, (value - occt[0]).Modulus() / std::max(1.0, occt[0].Modulus()));
            double one[9];
            curve.eval_into(ts[i], 2, one, 9);
            double value_one[3];
            curve.eval_into(ts[i], 0, value_one, 3);
            if (std::memcmp(one, &jets[i * 9], sizeof one) == 0 &&
                std::memcmp(value_one, &values[i * 3], sizeof value_one) == 0) {
                ++same_bits;
            }
        }
        report.row(worst <= 1e-12 && same_bits == count, name, worst, 1e-12,
                   format("%zu parameters, orders 0 and 0..2, relative; blocks equal to bzj_curve_eval's "
                          "bits: %zu of %zu",
                          count, same_bits, count));
    });
}

void time_evaluation(Report& report, std::vector<Timing>& timings, const Options& options) {
    guarded(report, "timing.eval", [&] {
        const int batches = options.quick ? 1 : 15;
        const int calls = options.quick ? 10 : 200000;
        for (std::size_t degree : {3u, 7u}) {
            std::mt19937_64 rng(7 + degree);
            const Curve curve(3, degree, random_points(rng, 3, degree));
            const Handle(Geom_BezierCurve) occ = occ_bezier(curve);
            std::vector<double> params(1024);
            for (std::size_t i = 0; i < params.size(); ++i) {
                params[i] = (i * 0.6180339887498949) - std::floor(i * 0.6180339887498949);
            }
            double buffer[3];
            gp_Pnt p;
            // One value of `c` per call, at the i-th of the 1024 parameters.
            const auto value_of = [&](const Curve& c) {
                return [&, handle = &c](int i) {
                    handle->eval_into(params[i & 1023], 0, buffer, 3);
                    g_sink = g_sink + buffer[0];
                };
            };
            const auto bezier_value = value_of(curve);
            const Pair pair = time_pair(
                batches, calls, bezier_value,
                calls,
                [&](int i) {
                    occ->D0(params[i & 1023], p);
                    g_sink = g_sink + p.X();
                });
            timings.push_back({format("evaluation, degree %zu 3D", degree), "bzj_curve_eval order 0",
                               "Geom_BezierCurve::D0", pair});

            // eval_many: one call for 1000 parameters against 1000 calls of
            // D0 (times per 1000 points; the ratio is per point).
            const std::size_t count = 1000;
            std::vector<double> many(count * 3);
            check_eval_many(report, curve, occ, params, count, degree);
            const Pair many_pair = time_pair(
                batches, std::max(1, calls / static_cast<int>(count)),
                [&](int) {
                    bzj_curve_eval_many(curve.get(), params.data(), count, 0, many.data(), many.size());
                    g_sink = g_sink + many[3 * count - 1];
                },
                std::max(1, calls / static_cast<int>(count)),
                [&](int) {
                    for (std::size_t i = 0; i < count; ++i) {
                        occ->D0(params[i], p);
                        g_sink = g_sink + p.X();
                    }
                });
            timings.push_back({format("eval_many 1000 points, degree %zu 3D", degree),
                               "bzj_curve_eval_many order 0", "1000 x D0", many_pair});

            // The same curve as a NURBS handle (one span) against OCCT's
            // B-spline of it; and our NURBS time beside our Bezier time.
            const Curve nurbs = curve.to_nurbs();
            const Handle(Geom_BSplineCurve) occ_nurbs = GeomConvert::CurveToBSplineCurve(occ);
            double worst = 0.0;
            for (std::size_t i = 0; i < count; ++i) {
                nurbs.eval_into(params[i], 0, buffer, 3);
                occ_nurbs->D0(params[i], p);
                const double scale = std::max(1.0, p.XYZ().Modulus());
                worst = std::max(worst, gp_Pnt(buffer[0], buffer[1], buffer[2]).Distance(p) / scale);
            }
            report.row(worst <= 1e-12, format("b.nurbs-eval-vs-BSpline-D0[deg %zu]", degree), worst, 1e-12,
                       "the Bezier as a one-span NURBS handle, 1000 parameters, relative");
            const auto nurbs_value = value_of(nurbs);
            const Pair nurbs_pair = time_pair(
                batches, calls, nurbs_value,
                calls,
                [&](int i) {
                    occ_nurbs->D0(params[i & 1023], p);
                    g_sink = g_sink + p.X();
                });
            timings.push_back({format("NURBS evaluation, degree %zu 3D (one span)", degree),
                               "bzj_curve_eval order 0", "Geom_BSplineCurve::D0", nurbs_pair});
            // Issue 20's "NURBS within 2x of Bezier": the two handles in
            // alternating batches of their own, the median of the per-batch
            // ratios, as every TIME row (the times of the two rows above come
            // from different minutes, and a noisy machine moved their quotient
            // from 1.7x to 2.1x for the same library, session 40).
            const Pair versus = time_pair(batches, calls, bezier_value, calls, nurbs_value);
            report.info(format("timing.nurbs-vs-bezier[deg %zu]", degree),
                        format("our NURBS handle %s, our Bezier handle %s per value: %.2fx the Bezier time "
                               "(median over %d alternating batches)",
                               format_time(versus.occt_ns).c_str(), format_time(versus.ours_ns).c_str(),
                               versus.ratio, batches));
        }
        // The cost of one trip through the C ABI (guard, status, last-error
        // bookkeeping) on a function that does no work: part of every call.
        const Curve curve(3, 3, std::vector<double>(12, 0.5));
        const double trip = time_per_call_ns(batches, calls, [&](int) {
            std::size_t degree = 0;
            bzj_curve_degree(curve.get(), &degree);
            g_sink = g_sink + static_cast<double>(degree);
        });
        report.info("timing.c-abi-call-overhead",
                    format("bzj_curve_degree (no work): %s per call", format_time(trip).c_str()));
    });
}

// The connect system C R = F assembled with OCCT's B-spline basis
// (BSplCLib::EvalBsplineBasis on the Bezier knot vector) and right-hand side
// (Geom_BezierCurve::DN), solved per coordinate with math_Gauss. Returns R's
// control points row-major (dim 3).
std::vector<double> occt_connect(const Handle(Geom_BezierCurve)& p, double u0,
                                 const Handle(Geom_BezierCurve)& q, double v0, int kp, int kq,
                                 double alpha, double beta) {
    const int degree = kp + kq + 1;
    const int order = degree + 1;
    TColStd_Array1OfReal flat_knots(1, 2 * order);
    for (int i = 1; i <= order; ++i) {
        flat_knots(i) = 0.0;
        flat_knots(order + i) = 1.0;
    }
    math_Matrix system(1, order, 1, order, 0.0);
    math_Matrix rhs(1, order, 1, 3, 0.0);
    math_Matrix basis(1, kp + 1, 1, order, 0.0);
    int first = 0;
    BSplCLib::EvalBsplineBasis(kp, order, flat_knots, 0.0, first, basis);
    for (int k = 0; k <= kp; ++k) {
        for (int j = 1; j <= order; ++j) {
            system(k + 1, first + j - 1) = basis(k + 1, j);
        }
        const gp_Vec d = k == 0 ? gp_Vec(p->Value(u0).XYZ()) : p->DN(u0, k);
        const double s = std::pow(alpha, k);
        rhs(k + 1, 1) = s * d.X();
        rhs(k + 1, 2) = s * d.Y();
        rhs(k + 1, 3) = s * d.Z();
    }
    math_Matrix basis_end(1, kq + 1, 1, order, 0.0);
    BSplCLib::EvalBsplineBasis(kq, order, flat_knots, 1.0, first, basis_end);
    for (int k = 0; k <= kq; ++k) {
        const int row = kp + 2 + k;
        for (int j = 1; j <= order; ++j) {
            system(row, first + j - 1) = basis_end(k + 1, j);
        }
        const gp_Vec d = k == 0 ? gp_Vec(q->Value(v0).XYZ()) : q->DN(v0, k);
        const double s = std::pow(beta, k);
        rhs(row, 1) = s * d.X();
        rhs(row, 2) = s * d.Y();
        rhs(row, 3) = s * d.Z();
    }
    math_Gauss gauss(system);
    if (!gauss.IsDone()) {
        throw std::runtime_error("math_Gauss: singular connect system");
    }
    std::vector<double> out(static_cast<std::size_t>(order) * 3);
    for (int c = 1; c <= 3; ++c) {
        math_Vector b(1, order);
        for (int i = 1; i <= order; ++i) {
            b(i) = rhs(i, c);
        }
        math_Vector x(1, order);
        gauss.Solve(b, x);
        for (int i = 1; i <= order; ++i) {
            out[(i - 1) * 3 + (c - 1)] = x(i);
        }
    }
    return out;
}

// The floor of the connect row (cpp-demo/connect_floor.cpp, issue 20): an
// unchecked connect written out for the demo's case only. Its control points
// must be bzj_connect's (a row); its time against OCCT's route, next to
// bzj_connect's, is printed as information: how far the checked, general
// connect is from the least any connect of this case can cost here.
Curve ours_from_occ(const Handle(Geom_BSplineCurve)& c, std::size_t dim);
void check_connect_nurbs_inputs(Report& report, const Curve& p, const Curve& q,
                                const Handle(Geom_BezierCurve)& occ_p, const Handle(Geom_BezierCurve)& occ_q,
                                double u0, double v0, const bezjoin::ConnectOptions& opts, int batches, int calls);

void check_connect_floor(Report& report, bool demo_case, const std::vector<double>& p_points,
                         const std::vector<double>& q_points, double u0, double v0,
                         const std::vector<double>& ours, const Handle(Geom_BezierCurve)& occ_p,
                         const Handle(Geom_BezierCurve)& occ_q, const Pair& connect_pair,
                         const Options& options) {
    if (!demo_case) {
        throw std::runtime_error("connect floor: written for the cubic + quartic C3/C4 case only");
    }
    ConnectFloor* floor = connect_floor(p_points.data(), u0, q_points.data(), v0);
    if (floor == nullptr) {
        throw std::runtime_error("connect floor: out of memory");
    }
    double gap = ours.size() == floor->count * 3 ? 0.0 : INFINITY;
    for (std::size_t i = 0; i < std::min(ours.size(), floor->count * 3); ++i) {
        gap = std::max(gap, std::abs(ours[i] - floor->points[i]));
    }
    gap /= std::max(1.0, max_abs(ours));
    const double residual = floor->residual;
    connect_floor_free(floor);
    report.row(gap <= 1e-12 && residual <= 1e-12, "c.connect-floor-vs-bzj_connect", std::max(gap, residual), 1e-12,
               "control points of the unchecked kernel written for this case (connect_floor.cpp) "
               "against bzj_connect's, and its own largest residual");
    const int batches = options.quick ? 1 : 11;
    const int calls = options.quick ? 2 : 10000;
    const Pair pair = time_pair(
        batches, calls,
        [&](int) {
            ConnectFloor* f = connect_floor(p_points.data(), u0, q_points.data(), v0);
            g_sink = g_sink + f->points[0] + f->residual;
            connect_floor_free(f);
        },
        calls,
        [&](int) {
            const std::vector<double> x = occt_connect(occ_p, u0, occ_q, v0, 3, 4, 1.0, 1.0);
            g_sink = g_sink + x[0];
        });
    report.info("timing.connect-floor",
                format("unchecked kernel for this case only %s (%.1fx OCCT's %s); bzj_connect %s (%.1fx), "
                       "%.1fx the floor; 20x OCCT needs %s",
                       format_time(pair.ours_ns).c_str(), pair.ratio, format_time(pair.occt_ns).c_str(),
                       format_time(connect_pair.ours_ns).c_str(), connect_pair.ratio,
                       connect_pair.ours_ns / pair.ours_ns, format_time(connect_pair.occt_ns / 20.0).c_str()));
}

// c. connect: the chain P|[0,u0], R, Q|[v0,1] on knot intervals
// (u0, alpha, (1-v0) alpha/beta) is C^kp / C^kq by OCCT's judgement.
void check_connect(Report& report, StepScene& scene, std::vector<Timing>& timings,
                   const Options& options) {
    struct Case {
        const char* name;
        std::size_t np, nq, kp, kq;
        double u0, v0, alpha, beta;
        bool constraint;
    };
    const Case cases[] = {
        {"paper kp=np kq=nq", 3, 4, 3, 4, 0.6, 0.3, 1.0, 1.0, false},
        {"scaled + point", 5, 3, 2, 3, 0.8, 0.25, 1.7, 0.6, true},
    };
    const double tolerance = 1e-9;
    int index = 0;
    for (const Case& cs : cases) {
        const std::string name = format("c.connect[%s]", cs.name);
        guarded(report, name, [&] {
            std::mt19937_64 rng(100 + index);
            std::vector<double> p_points = random_points(rng, 3, cs.np);
            std::vector<double> q_points = random_points(rng, 3, cs.nq);
            for (std::size_t i = 0; i <= cs.nq; ++i) {
                q_points[i * 3] += 2.5;  // Q to the right of P: a real gap to bridge
            }
            const Curve p(3, cs.np, p_points);
            const Curve q(3, cs.nq, q_points);
            bezjoin::ConnectOptions opts;
            opts.p_order = cs.kp;
            opts.q_order = cs.kq;
            opts.p_scale = cs.alpha;
            opts.q_scale = cs.beta;
            bezjoin::PointConstraint point;
            if (cs.constraint) {
                point.t = 0.4;
                point.max_order = 1;
                point.values = {1.2, 0.9, -0.3, 2.0, 0.5, 0.4};  // R(0.4), R'(0.4)
                opts.constraints.push_back(point);
            }
            const Curve r = bezjoin::connect(p, cs.u0, q, cs.v0, opts);
            const Curve p_part = p.segment(0.0, cs.u0);
            const Curve q_part = q.segment(cs.v0, 1.0);
            const double intervals_q = (1.0 - cs.v0) * cs.alpha / cs.beta;
            const Chain chain = make_chain({&p_part, &r, &q_part}, {cs.u0, cs.alpha, intervals_q});
            const JoinVerdict left = judge_join(chain, 2, static_cast<int>(cs.kp), tolerance * chain.size);
            const JoinVerdict right = judge_join(chain, 3, static_cast<int>(cs.kq), tolerance * chain.size);
            double worst = std::max({left.jump, right.jump, chain.pole_gap});
            bool pass = left.removable && right.removable && worst <= tolerance;
            std::string note = format(
                "degree %d; RemoveKnot to mult %d at P|R: %s, to %d at R|Q: %s; C^(k+1) too: %s/%s",
                chain.degree, chain.degree - static_cast<int>(cs.kp), left.removable ? "ok" : "REFUSED",
                chain.degree - static_cast<int>(cs.kq), right.removable ? "ok" : "REFUSED",
                left.stricter ? "yes" : "no", right.stricter ? "yes" : "no");
            if (cs.constraint) {
                // R(t0) and R'(t0) through OCCT's chain: global u = u0 + alpha t0.
                const double u = cs.u0 + cs.alpha * point.t;
                const gp_Pnt value = chain.curve->Value(u);
                const gp_Vec tangent = chain.curve->DN(u, 1) * cs.alpha;
                const gp_Pnt wanted(point.values[0], point.values[1], point.values[2]);
                const gp_Vec wanted_tangent(point.values[3], point.values[4], point.values[5]);
                const double miss = std::max(value.Distance(wanted) / chain.size,
                                             (tangent - wanted_tangent).Magnitude() /
                                                 std::max(1.0, wanted_tangent.Magnitude()));
                worst = std::max(worst, miss);
                pass = pass && miss <= tolerance;
                note += format("; constraint miss %.1e", miss);
            }
            report.row(pass, name, worst, tolerance, note);

            if (!cs.constraint) {
                // The same system through OCCT: assemble + math_Gauss.
                const Handle(Geom_BezierCurve) occ_p = occ_bezier(p);
                const Handle(Geom_BezierCurve) occ_q = occ_bezier(q);
                const std::vector<double> theirs =
                    occt_connect(occ_p, cs.u0, occ_q, cs.v0, static_cast<int>(cs.kp),
                                 static_cast<int>(cs.kq), cs.alpha, cs.beta);
                const std::vector<double> ours = r.points();
                const double gap = relative_gap(ours, theirs);
                report.row(gap <= 1e-10, "c.connect-vs-math_Gauss", gap, 1e-10,
                           format("control points of R (degree %zu), OCCT-assembled system",
                                  cs.kp + cs.kq + 1));

                const int batches = options.quick ? 1 : 11;
                const int calls = options.quick ? 2 : 10000;
                const Pair pair = time_pair(
                    batches, calls,
                    [&](int) {
                        const Curve joined = bezjoin::connect(p, cs.u0, q, cs.v0, opts);
                        g_sink = g_sink + static_cast<double>(joined.degree());
                    },
                    calls,
                    [&](int) {
                        const std::vector<double> x =
                            occt_connect(occ_p, cs.u0, occ_q, cs.v0, static_cast<int>(cs.kp),
                                         static_cast<int>(cs.kq), cs.alpha, cs.beta);
                        g_sink = g_sink + x[0];
                    });
                timings.push_back({format("connect C3/C4 (cubic + quartic, degree %zu)", cs.kp + cs.kq + 1),
                                   "bzj_connect", "EvalBsplineBasis + DN + math_Gauss", pair});
                check_connect_floor(report, cs.np == 3 && cs.nq == 4 && cs.kp == 3 && cs.kq == 4 &&
                                                cs.alpha == 1.0 && cs.beta == 1.0,
                                    p_points, q_points, cs.u0, cs.v0, ours, occ_p, occ_q, pair, options);
                if (cs.np == 3 && cs.nq == 4 && cs.kp == 3 && cs.kq == 4) {
                    check_connect_nurbs_inputs(report, p, q, occ_p, occ_q, cs.u0, cs.v0, opts, batches, calls);
                }
                const gp_Vec offset(0.0, 0.0, 0.0);
                scene.add(Handle(Geom_Curve)(chain.curve), offset);
            }
        });
        ++index;
    }
    expect_status(report, "c.connect-error-u0-outside", BZJ_ERR_INVALID_ARGUMENT, [&] {
        const Curve p(2, 2, {0.0, 0.0, 1.0, 1.0, 2.0, 0.0});
        bezjoin::ConnectOptions opts;
        opts.p_order = 1;
        opts.q_order = 1;
        (void)bezjoin::connect(p, 1.5, p, 0.0, opts);
    });
    // Orders above the degree are accepted (c-api.md: "p_order, q_order may
    // exceed the degree"): the quadratic's third derivative, 0, is matched.
    guarded(report, "c.connect-order-above-degree", [&] {
        const Curve p(2, 2, {0.0, 0.0, 1.0, 1.0, 2.0, 0.0});
        bezjoin::ConnectOptions opts;
        opts.p_order = 3;
        opts.q_order = 2;
        const Curve r = bezjoin::connect(p, 0.5, p, 1.0, opts);
        const std::vector<double> jet = r.eval(0.0, 3);
        const double third = std::hypot(jet[6], jet[7]);
        report.row(r.degree() == 6 && third <= 1e-12, "c.connect-order-above-degree", third, 1e-12,
                   "|R^(3)(0)| for P^(3) = 0, kp = 3 on a quadratic");
    });
}

// n. NURBS handles (c-api.md "NURBS curves"): a multi-span rational B-spline
// against OCCT's Geom_BSplineCurve made of the same poles, weights, knots and
// multiplicities (values and first derivatives; the pieces of split, segment
// and bezier_spans at the original parameters); a circle arc on its circle,
// with its length; connect from the arc to a B-spline with orders above the
// degrees, P's jet from the left of a knot, Q's from the right.
void check_nurbs(Report& report) {
    const std::vector<double> poles = {0, 0, 0, 1, 2, 0.5, 3, 3, -1, 5, 1, 0, 6, -1, 2};
    const std::vector<double> weights = {1.0, 0.8, 1.3, 0.5, 1.0};
    const std::vector<double> knots = {0, 0, 0, 1, 2.5, 4, 4, 4};
    guarded(report, "n.nurbs-vs-Geom_BSplineCurve", [&] {
        const Curve ours = Curve::nurbs(3, 2, poles, knots, weights);
        TColgp_Array1OfPnt occ_poles(1, 5);
        TColStd_Array1OfReal occ_weights(1, 5);
        for (int i = 0; i < 5; ++i) {
            occ_poles.SetValue(i + 1, gp_Pnt(poles[3 * i], poles[3 * i + 1], poles[3 * i + 2]));
            occ_weights.SetValue(i + 1, weights[i]);
        }
        TColStd_Array1OfReal occ_knots(1, 4);
        TColStd_Array1OfInteger occ_mults(1, 4);
        const double distinct[] = {0.0, 1.0, 2.5, 4.0};
        const int mults[] = {3, 1, 1, 3};
        for (int i = 0; i < 4; ++i) {
            occ_knots.SetValue(i + 1, distinct[i]);
            occ_mults.SetValue(i + 1, mults[i]);
        }
        const Handle(Geom_BSplineCurve) occ =
            new Geom_BSplineCurve(occ_poles, occ_weights, occ_knots, occ_mults, 2);
        // Largest relative gap of value and first derivative between `curve`
        // at s and OCCT at u (the derivative scaled by `scale` = du/ds).
        auto gap = [&](const Curve& curve, double s, double u, double scale) {
            const std::vector<double> v = curve.eval(s, 1);
            gp_Pnt point;
            gp_Vec d1;
            occ->D1(u, point, d1);
            const double e0 = std::hypot(std::hypot(v[0] - point.X(), v[1] - point.Y()), v[2] - point.Z()) /
                              std::max(1.0, gp_Vec(point.XYZ()).Magnitude());
            const double e1 = std::hypot(std::hypot(v[3] - scale * d1.X(), v[4] - scale * d1.Y()),
                                         v[5] - scale * d1.Z()) /
                              std::max(1.0, scale * d1.Magnitude());
            return std::max(e0, e1);
        };
        double worst = 0.0;
        for (int i = 0; i <= 400; ++i) {
            const double u = 4.0 * i / 400.0;
            worst = std::max(worst, gap(ours, u, u, 1.0));
        }
        report.row(worst <= 1e-13, "n.nurbs-vs-Geom_BSplineCurve", worst, 1e-13,
                   "value and C' at 401 parameters, 3 rational spans");
        const Curve copy = ours.to_nurbs();
        const bool round_trip = ours.is_nurbs() && ours.is_rational() && ours.pole_count() == 5 &&
                                ours.weights() == weights && ours.knots() == knots &&
                                copy.points() == poles && copy.weights() == weights &&
                                ours.domain() == std::make_pair(0.0, 4.0);
        report.row(round_trip, "n.inspection-round-trip", 0.0, 0.0,
                   "pole_count, points, weights, knots, domain, to_nurbs");
        double pieces = 0.0;
        const auto halves = ours.split(1.7);
        const Curve middle = ours.segment(0.6, 3.1);
        for (int i = 0; i <= 100; ++i) {
            const double t = i / 100.0;
            pieces = std::max(pieces, gap(halves.first, 1.7 * t, 1.7 * t, 1.0));
            pieces = std::max(pieces, gap(halves.second, 1.7 + 2.3 * t, 1.7 + 2.3 * t, 1.0));
            pieces = std::max(pieces, gap(middle, 0.6 + 2.5 * t, 0.6 + 2.5 * t, 1.0));
        }
        const std::vector<Curve> spans = ours.bezier_spans();
        bool kinds = spans.size() == 3;
        for (std::size_t k = 0; k < spans.size() && k < 3; ++k) {
            const double a = distinct[k];
            const double b = distinct[k + 1];
            kinds = kinds && spans[k].is_nurbs() == spans[k].is_rational();
            for (int i = 0; i <= 50; ++i) {
                const double t = i / 50.0;
                const double u = a + (b - a) * t;
                pieces = std::max(pieces, spans[k].is_nurbs() ? gap(spans[k], u, u, 1.0)
                                                              : gap(spans[k], t, u, b - a));
            }
        }
        report.row(kinds && pieces <= 1e-13, "n.split-segment-spans-vs-OCCT", pieces, 1e-13,
                   "pieces at the original parameters (Bezier spans on [0, 1])");
    });
    guarded(report, "n.ellipse-arc-on-circle", [&] {
        const double pi = 3.14159265358979323846;
        const Curve arc = Curve::ellipse_arc(3, {1.0, 2.0, 3.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0},
                                             2.5, 2.5, 0.25, 0.25 + 1.75 * pi);
        double worst = 0.0;
        const auto domain = arc.domain();
        for (int i = 0; i <= 700; ++i) {
            const double u = domain.first + (domain.second - domain.first) * i / 700.0;
            const std::vector<double> v = arc.eval(u);
            const double r = std::hypot(std::hypot(v[0] - 1.0, v[1] - 2.0), v[2] - 3.0);
            worst = std::max(worst, std::fabs(r - 2.5) / 2.5 + std::fabs(v[0] - 1.0));
        }
        const double length_gap = std::fabs(arc.length() - 2.5 * 1.75 * pi) / (2.5 * 1.75 * pi);
        report.row(worst <= 2e-15 && length_gap <= 1e-12, "n.ellipse-arc-on-circle",
                   std::max(worst, length_gap), 1e-12, "radius and length of a 315 degree arc");
    });
    guarded(report, "n.connect-arc-to-bspline", [&] {
        const double pi = 3.14159265358979323846;
        const Curve arc = Curve::ellipse_arc(2, {0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, 1.0, 1.0, 0.0, pi);
        const Curve q = Curve::nurbs(2, 3, {3, 0, 4, 1, 5, 3, 6, 2, 7, 0, 8, 1},
                                     {0, 0, 0, 0, 0.5, 0.5, 1, 1, 1, 1});
        const double u0 = arc.knots()[3];  // the knot at pi/2
        bezjoin::ConnectOptions opts;
        opts.p_order = 4;
        opts.q_order = 5;
        const Curve r = bezjoin::connect(arc, u0, q, 0.5, opts);
        const std::vector<double> p_jet = arc.split(u0).first.eval(u0, 4);  // from the left
        const std::vector<double> q_jet = q.eval(0.5, 5);                  // from the right
        const std::vector<double> r0 = r.eval(0.0, 4);
        const std::vector<double> r1 = r.eval(1.0, 5);
        double worst = 0.0;
        for (std::size_t i = 0; i < r0.size(); ++i) {
            worst = std::max(worst, std::fabs(r0[i] - p_jet[i]) / std::max(1.0, std::fabs(p_jet[i])));
        }
        for (std::size_t i = 0; i < r1.size(); ++i) {
            worst = std::max(worst, std::fabs(r1[i] - q_jet[i]) / std::max(1.0, std::fabs(q_jet[i])));
        }
        report.row(!r.is_nurbs() && r.degree() == 10 && worst <= 1e-8, "n.connect-arc-to-bspline",
                   worst, 1e-8, "C^4 / C^5 at knots, orders above the degrees 2 and 3");
    });
}

// ---------------------------------------------------------------- NURBS judged by OCCT (issue 16 item 5)
//
// Rows "n.DN[...]", "n.segment[...]", "n.ellipse[...]", "n.fillet_vertex[...]",
// "n.fillet[...]", "n.ChFi2d[...]": our NURBS paths against OCCT's
// Geom_BSplineCurve (DN, Segment), GC_MakeArcOfEllipse / GC_MakeCircle, and
// the C^k of fillets judged by RemoveKnot on one Geom_BSplineCurve made of
// P_trim, R and Q_trim; ChFi2d_FilletAPI on the same arc-line corner.

// Row k (dim doubles) of a jet from Curve::eval as a 3D vector (z = 0 in 2D).
gp_Vec jet_row(const std::vector<double>& jet, std::size_t k, std::size_t dim) {
    const double* r = &jet[k * dim];
    return gp_Vec(r[0], dim > 1 ? r[1] : 0.0, dim > 2 ? r[2] : 0.0);
}

// Distinct knots and their multiplicities of a flat knot vector.
void distinct_knots(const std::vector<double>& flat, std::vector<double>& knots, std::vector<int>& mults) {
    knots.clear();
    mults.clear();
    for (double k : flat) {
        if (!knots.empty() && k == knots.back()) {
            ++mults.back();
        } else {
            knots.push_back(k);
            mults.push_back(1);
        }
    }
}

TColStd_Array1OfReal occ_reals(const std::vector<double>& v) {
    TColStd_Array1OfReal out(1, static_cast<int>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) {
        out(static_cast<int>(i) + 1) = v[i];
    }
    return out;
}

TColStd_Array1OfInteger occ_ints(const std::vector<int>& v) {
    TColStd_Array1OfInteger out(1, static_cast<int>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) {
        out(static_cast<int>(i) + 1) = v[i];
    }
    return out;
}

// OCCT's B-spline of our curve (NURBS or Bezier, 2D lifted to z = 0): the
// same poles, weights and knots (distinct knots + multiplicities).
Handle(Geom_BSplineCurve) occ_bspline(const Curve& c) {
    std::vector<double> knots;
    std::vector<int> mults;
    distinct_knots(c.knots(), knots, mults);
    return new Geom_BSplineCurve(poles3(c.points(), c.dim()), occ_reals(c.weights()), occ_reals(knots),
                                 occ_ints(mults), static_cast<int>(c.degree()));
}

Handle(Geom2d_BSplineCurve) occ_bspline2d(const Curve& c) {
    std::vector<double> knots;
    std::vector<int> mults;
    distinct_knots(c.knots(), knots, mults);
    const std::vector<double> points = c.points();
    TColgp_Array1OfPnt2d poles(1, static_cast<int>(points.size() / 2));
    for (int i = poles.Lower(); i <= poles.Upper(); ++i) {
        poles(i) = gp_Pnt2d(points[2 * (i - 1)], points[2 * (i - 1) + 1]);
    }
    return new Geom2d_BSplineCurve(poles, occ_reals(c.weights()), occ_reals(knots), occ_ints(mults),
                                   static_cast<int>(c.degree()));
}

// Our NURBS handle of an OCCT B-spline (dim 2 reads x and y) through
// bzj_nurbs_new. A periodic curve is written unclamped: its poles with the
// first `degree` repeated at the end, on OCCT's flat knot sequence
// (KnotSequence) -- the same curve on [FirstParameter, LastParameter].
Curve ours_from_occ(const Handle(Geom_BSplineCurve)& c, std::size_t dim) {
    const int degree = c->Degree();
    const int n = c->NbPoles();
    const int count = c->IsPeriodic() ? n + degree : n;
    std::vector<double> poles;
    std::vector<double> weights;
    for (int i = 0; i < count; ++i) {
        const int j = i % n + 1;
        const gp_Pnt p = c->Pole(j);
        for (std::size_t d = 0; d < dim; ++d) {
            poles.push_back(p.Coord(static_cast<int>(d) + 1));
        }
        if (c->IsRational()) {
            weights.push_back(c->Weight(j));
        }
    }
    const TColStd_Array1OfReal& sequence = c->KnotSequence();
    std::vector<double> knots;
    for (int i = sequence.Lower(); i <= sequence.Upper(); ++i) {
        knots.push_back(sequence(i));
    }
    if (knots.size() != static_cast<std::size_t>(count + degree + 1)) {
        throw std::runtime_error(format("ours_from_occ: %zu flat knots for %d poles of degree %d", knots.size(),
                                        count, degree));
    }
    return Curve::nurbs(dim, static_cast<std::size_t>(degree), poles, knots, weights);
}

// Issue 20's "NURBS inputs within 2x their Bezier counterparts" for connect.
// bzj_connect of the demo's cubic and quartic as Bezier handles against:
// - the same curves as NURBS handles of two spans (GeomConvert, then OCCT's
//   InsertKnot at 0.5: the same geometry, so the same connecting curve up to
//   rounding, checked);
// - a rational copy of those two spans (SetWeight, weights 0.7 to 1.3 inside,
//   1 at the ends: other geometry of the same sizes and degrees).
// Alternating batches, the median of the per-batch ratios (as every TIME row).
void check_connect_nurbs_inputs(Report& report, const Curve& p, const Curve& q,
                                const Handle(Geom_BezierCurve)& occ_p, const Handle(Geom_BezierCurve)& occ_q,
                                double u0, double v0, const bezjoin::ConnectOptions& opts, int batches, int calls) {
    auto two_spans = [](const Handle(Geom_BezierCurve)& bezier, const std::vector<double>& weights) {
        Handle(Geom_BSplineCurve) c = GeomConvert::CurveToBSplineCurve(bezier);
        c->InsertKnot(0.5);
        for (std::size_t i = 0; i < weights.size() && static_cast<int>(i) < c->NbPoles(); ++i) {
            c->SetWeight(static_cast<int>(i) + 1, weights[i]);
        }
        return c;
    };
    const Curve p_spans = ours_from_occ(two_spans(occ_p, {}), 3);
    const Curve q_spans = ours_from_occ(two_spans(occ_q, {}), 3);
    const Curve p_rational = ours_from_occ(two_spans(occ_p, {1.0, 0.7, 1.3, 0.9, 1.0}), 3);
    const Curve q_rational = ours_from_occ(two_spans(occ_q, {1.0, 1.2, 0.8, 1.1, 0.7, 1.0}), 3);
    const std::vector<double> bezier_poles = bezjoin::connect(p, u0, q, v0, opts).points();
    const std::vector<double> span_poles = bezjoin::connect(p_spans, u0, q_spans, v0, opts).points();
    const double gap = relative_gap(span_poles, bezier_poles);
    const bool rational = p_rational.is_rational() && q_rational.is_rational() && p_spans.pole_count() == 5 &&
                          q_spans.pole_count() == 6;
    report.row(gap <= 1e-12 && rational, "c.connect-nurbs-inputs", gap, 1e-12,
               format("the cubic and quartic as two-span NURBS (%zu and %zu poles, knot 0.5) give R's poles as the "
                      "Bezier handles do; rational copies built: %s",
                      p_spans.pole_count(), q_spans.pole_count(), rational ? "yes" : "NO"));
    auto timed = [&](const Curve& a, const Curve& b) {
        return [&, pa = &a, pb = &b](int) {
            const Curve joined = bezjoin::connect(*pa, u0, *pb, v0, opts);
            g_sink = g_sink + static_cast<double>(joined.degree());
        };
    };
    const Pair spans = time_pair(batches, calls, timed(p, q), calls, timed(p_spans, q_spans));
    const Pair weighted = time_pair(batches, calls, timed(p, q), calls, timed(p_rational, q_rational));
    report.info("timing.connect-nurbs-vs-bezier",
                format("bzj_connect C3/C4 with two-span NURBS inputs %s (%.2fx the Bezier inputs' %s), with "
                       "rational two-span inputs %s (%.2fx the Bezier inputs' %s); goal <= 2x (median over %d "
                       "alternating batches)",
                       format_time(spans.occt_ns).c_str(), spans.ratio, format_time(spans.ours_ns).c_str(),
                       format_time(weighted.occt_ns).c_str(), weighted.ratio,
                       format_time(weighted.ours_ns).c_str(), batches));
}

// The value and derivatives 1..3 of OCCT's curve at u. from == 0: Value and
// DN (OCCT's DN takes the span on the right of an interior knot, like
// bzj_curve_eval); else LocalValue / LocalDN on the span between knots
// `from` and `to` (the left side of a knot, the last span at the end).
void occ_jet(const Handle(Geom_BSplineCurve)& c, double u, int from, int to, gp_Vec out[4]) {
    if (from == 0) {
        out[0] = gp_Vec(c->Value(u).XYZ());
        for (int k = 1; k <= 3; ++k) {
            out[k] = c->DN(u, k);
        }
    } else {
        out[0] = gp_Vec(c->LocalValue(u, from, to).XYZ());
        for (int k = 1; k <= 3; ++k) {
            out[k] = c->LocalDN(u, from, to, k);
        }
    }
}

// Our curve against OCCT's at the domain ends, every interior knot (right
// side: ours' eval and OCCT's DN; left side: our piece split there, whose
// domain ends at the knot, against OCCT's LocalDN on the span before it) and
// `random` parameters: relative errors per order 0..3 (relative to max |C^(k)|
// over the samples), the left sides separately.
struct JetComparison {
    double error[4] = {0.0, 0.0, 0.0, 0.0};
    double ours_ref[4] = {0.0, 0.0, 0.0, 0.0};  // with a reference curve: ours vs it
    double occt_ref[4] = {0.0, 0.0, 0.0, 0.0};  // OCCT's curve vs it
    double left = 0.0;
    std::size_t samples = 0;
    std::size_t knots = 0;
    double domain_gap = 0.0;
    double worst() const { return std::max({error[0], error[1], error[2], error[3], left, domain_gap}); }
};

// The same side of `reference` (a curve the two are pieces of): at one of
// its knots the span on the requested side, at its end its last span.
void reference_jet(const Handle(Geom_BSplineCurve)& c, double u, bool left, gp_Vec out[4]) {
    int from = 0;
    int to = 0;
    if (u >= c->LastParameter()) {
        from = c->LastUKnotIndex() - 1;
        to = c->LastUKnotIndex();
    } else if (left) {
        for (int i = c->FirstUKnotIndex() + 1; i <= c->LastUKnotIndex(); ++i) {
            if (c->Knot(i) == u) {
                from = i - 1;
                to = i;
            }
        }
    }
    occ_jet(c, u, from, to, out);
}

JetComparison compare_jets(const Curve& ours, const Handle(Geom_BSplineCurve)& occ, std::mt19937_64& rng,
                           int random, const Handle(Geom_BSplineCurve)& reference = nullptr) {
    JetComparison r;
    const std::size_t dim = ours.dim();
    const double first = occ->FirstParameter();
    const double last = occ->LastParameter();
    const std::pair<double, double> domain = ours.domain();
    r.domain_gap = std::max(std::abs(domain.first - first), std::abs(domain.second - last)) /
                   std::max({1.0, std::abs(first), std::abs(last)});
    const int first_index = occ->FirstUKnotIndex();
    const int last_index = occ->LastUKnotIndex();
    struct Sample {
        std::vector<double> ours;
        gp_Vec occ[4];
        gp_Vec ref[4];
        bool left;
    };
    std::vector<Sample> samples;
    auto add = [&](double u, bool left, int from, int to) {
        Sample s;
        s.left = left;
        s.ours = left ? ours.split(u).first.eval(u, 3) : ours.eval(u, 3);
        occ_jet(occ, u, from, to, s.occ);
        if (!reference.IsNull()) {
            reference_jet(reference, u, left || u >= last, s.ref);
        }
        samples.push_back(std::move(s));
    };
    add(first, false, 0, 0);
    add(last, false, last_index - 1, last_index);  // the last span, as ours
    for (int i = first_index + 1; i < last_index; ++i) {
        add(occ->Knot(i), false, 0, 0);
        add(occ->Knot(i), true, i - 1, i);
        ++r.knots;
    }
    std::uniform_real_distribution<double> uniform(first, last);
    for (int i = 0; i < random; ++i) {
        const double u = uniform(rng);
        bool near_knot = false;
        for (int j = first_index; j <= last_index; ++j) {
            near_knot = near_knot || std::abs(u - occ->Knot(j)) <= 1e-9 * (last - first);
        }
        if (!near_knot) {
            add(u, false, 0, 0);
        }
    }
    double scale[4] = {0.0, 0.0, 0.0, 0.0};
    for (const Sample& s : samples) {
        for (int k = 0; k <= 3; ++k) {
            scale[k] = std::max(scale[k], s.occ[k].Magnitude());
        }
    }
    for (const Sample& s : samples) {
        for (int k = 0; k <= 3; ++k) {
            // A derivative that is 0 throughout (order above the degree):
            // absolute error against the curve's size.
            const double denominator = scale[k] > 0.0 ? scale[k] : std::max(1.0, scale[0]);
            const double e = (jet_row(s.ours, static_cast<std::size_t>(k), dim) - s.occ[k]).Magnitude() /
                             denominator;
            if (s.left) {
                r.left = std::max(r.left, e);
            } else {
                r.error[k] = std::max(r.error[k], e);
            }
            if (!reference.IsNull()) {
                const gp_Vec mine = jet_row(s.ours, static_cast<std::size_t>(k), dim);
                r.ours_ref[k] = std::max(r.ours_ref[k], (mine - s.ref[k]).Magnitude() / denominator);
                r.occt_ref[k] = std::max(r.occt_ref[k], (s.occ[k] - s.ref[k]).Magnitude() / denominator);
            }
        }
    }
    r.samples = samples.size();
    return r;
}

// A random OCCT B-spline: `spans` spans in the domain, random weights in
// [0.3, 3], interior multiplicities cycling through 1..degree; ends clamped,
// unclamped (multiplicity 1 with `degree` more knots beyond each end) or
// periodic.
enum class Ends { clamped, unclamped, periodic };

Handle(Geom_BSplineCurve) random_occ_bspline(std::mt19937_64& rng, std::size_t dim, int degree, int spans,
                                             Ends ends, double start) {
    std::uniform_real_distribution<double> interval(0.2, 1.5);
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    std::uniform_real_distribution<double> weight(0.3, 3.0);
    const int outside = ends == Ends::unclamped ? degree : 0;
    const int count = spans + 1 + 2 * outside;
    std::vector<double> knots;
    std::vector<int> mults;
    double x = start;
    const int offset = static_cast<int>(rng() % static_cast<unsigned>(degree));
    for (int i = 0; i < count; ++i) {
        knots.push_back(x);
        x += interval(rng);
        const bool end = i == 0 || i == count - 1;
        int m = 1 + (i + offset) % degree;
        if (ends == Ends::clamped && end) {
            m = degree + 1;
        } else if (ends == Ends::unclamped && (i <= outside || i >= count - 1 - outside)) {
            m = 1;
        } else if (ends == Ends::periodic && end) {
            m = 1;
        }
        mults.push_back(m);
    }
    int total = 0;
    for (int m : mults) {
        total += m;
    }
    const int poles = ends == Ends::periodic ? total - mults.front() : total - degree - 1;
    TColgp_Array1OfPnt p(1, poles);
    TColStd_Array1OfReal w(1, poles);
    for (int i = 1; i <= poles; ++i) {
        p(i) = gp_Pnt(coordinate(rng), coordinate(rng), dim > 2 ? coordinate(rng) : 0.0);
        w(i) = weight(rng);
    }
    return new Geom_BSplineCurve(p, w, occ_reals(knots), occ_ints(mults), degree, ends == Ends::periodic);
}

struct NurbsCase {
    std::string name;
    std::size_t dim;
    Handle(Geom_BSplineCurve) occ;
    Curve ours;
};

std::string describe(const Handle(Geom_BSplineCurve)& c) {
    std::string mults;
    for (int i = 1; i <= c->NbKnots(); ++i) {
        mults += format("%s%d", i == 1 ? "" : ",", c->Multiplicity(i));
    }
    return format("%d poles, mults %s, domain [%.4g, %.4g]", c->NbPoles(), mults.c_str(), c->FirstParameter(),
                  c->LastParameter());
}

// 1. values and derivatives 0..3 against Geom_BSplineCurve::DN;
// 2. segment(a, b) against Geom_BSplineCurve::Segment(a, b).
void check_nurbs_dn_and_segment(Report& report, std::mt19937_64& rng, std::vector<Timing>& timings,
                                const Options& options) {
    const double tolerance = 1e-12;
    struct Spec {
        const char* name;
        std::size_t dim;
        int degree;
        Ends ends;
        double start;
    };
    const Spec specs[] = {
        {"deg2 3D clamped", 3, 2, Ends::clamped, -1.3},
        {"deg3 3D clamped", 3, 3, Ends::clamped, 10.0},
        {"deg4 2D clamped", 2, 4, Ends::clamped, 0.0},
        {"deg5 3D clamped", 3, 5, Ends::clamped, -7.5},
        {"deg3 3D unclamped", 3, 3, Ends::unclamped, 2.0},
        {"deg5 2D unclamped", 2, 5, Ends::unclamped, -3.0},
        {"deg4 3D periodic", 3, 4, Ends::periodic, 0.5},
        {"deg2 2D periodic", 2, 2, Ends::periodic, -1.0},
    };
    const int random = options.quick ? 60 : 400;
    std::vector<NurbsCase> cases;
    unsigned seed = 16000;
    for (const Spec& spec : specs) {
        const std::string name = format("n.DN[%s]", spec.name);
        std::mt19937_64 shape(++seed);  // the curve does not depend on --quick's sample counts
        guarded(report, name, [&] {
            const Handle(Geom_BSplineCurve) occ =
                random_occ_bspline(shape, spec.dim, spec.degree, spec.degree + 2, spec.ends, spec.start);
            Curve ours = ours_from_occ(occ, spec.dim);
            const JetComparison e = compare_jets(ours, occ, rng, random);
            const bool pass = ours.is_rational() && e.worst() <= tolerance;
            report.row(pass, name, e.worst(), tolerance,
                       format("%s; %zu samples incl. %zu knots both sides; orders 0-3: %.1e %.1e %.1e %.1e, "
                              "left of knots %.1e",
                              describe(occ).c_str(), e.samples, e.knots, e.error[0], e.error[1], e.error[2],
                              e.error[3], e.left));
            cases.push_back({spec.name, spec.dim, occ, std::move(ours)});
        });
    }
    // OCCT's DN at an interior knot is the right side (documented; checked
    // here on a C^0 knot), the side bzj_curve_eval takes.
    guarded(report, "n.DN-side-at-knots", [&] {
        const NurbsCase* c0 = nullptr;
        int index = 0;
        for (const NurbsCase& c : cases) {
            for (int i = c.occ->FirstUKnotIndex() + 1; i < c.occ->LastUKnotIndex() && !c0; ++i) {
                if (c.occ->Multiplicity(i) == c.occ->Degree()) {
                    c0 = &c;
                    index = i;
                }
            }
        }
        if (!c0) {
            throw std::runtime_error("no C^0 knot among the cases");
        }
        const double u = c0->occ->Knot(index);
        const gp_Vec dn = c0->occ->DN(u, 1);
        const gp_Vec right = c0->occ->LocalDN(u, index, index + 1, 1);
        const gp_Vec left = c0->occ->LocalDN(u, index - 1, index, 1);
        const gp_Vec ours = jet_row(c0->ours.eval(u, 1), 1, c0->dim);
        const double scale = std::max({1.0, right.Magnitude(), left.Magnitude()});
        const double to_right = (dn - right).Magnitude() / scale;
        const double ours_right = (ours - right).Magnitude() / scale;
        const double jump = (right - left).Magnitude() / scale;
        // At the domain's end OCCT's DN takes the last span, as ours (also on
        // a periodic curve, whose seam is not C^3 here).
        double at_end = 0.0;
        for (const NurbsCase& c : cases) {
            const int n = c.occ->LastUKnotIndex();
            const double last = c.occ->LastParameter();
            for (int k = 1; k <= 3; ++k) {
                const gp_Vec global = c.occ->DN(last, k);
                const gp_Vec local = c.occ->LocalDN(last, n - 1, n, k);
                at_end = std::max(at_end, (global - local).Magnitude() / std::max(1.0, local.Magnitude()));
            }
        }
        const bool pass = to_right <= tolerance && ours_right <= tolerance && jump > 1e-3 && at_end <= tolerance;
        report.row(pass, "n.DN-side-at-knots", std::max({to_right, ours_right, at_end}), tolerance,
                   format("%s, C^0 knot u = %.6g: OCCT DN - right span %.1e, ours - right %.1e, "
                          "|right - left| %.2e (a real jump); at the domain end OCCT's DN - last span %.1e "
                          "(%zu curves incl. periodic)",
                          c0->name.c_str(), u, to_right, ours_right, jump, at_end, cases.size()));
    });
    double short_ours[4] = {0.0, 0.0, 0.0, 0.0};
    double short_occt[4] = {0.0, 0.0, 0.0, 0.0};
    double short_between = 0.0;
    for (const NurbsCase& c : cases) {
        const std::string name = format("n.segment[%s]", c.name.c_str());
        guarded(report, name, [&] {
            const double first = c.occ->FirstParameter();
            const double last = c.occ->LastParameter();
            const int i0 = c.occ->FirstUKnotIndex();
            const int i1 = c.occ->LastUKnotIndex();
            const double k1 = c.occ->Knot(i0 + 1);
            const double k2 = c.occ->Knot(i1 - 1);
            const double span = c.occ->Knot(i0 + 2) - k1;
            const double h = last - first;
            // An end away from the knots (at least h / 50 from each), so no
            // piece gets an end span much shorter than the curve's spans.
            auto away = [&](double u) {
                for (int pass = 0; pass < 4; ++pass) {
                    for (int i = i0; i <= i1; ++i) {
                        if (std::abs(u - c.occ->Knot(i)) < h / 50.0) {
                            u = c.occ->Knot(i) + (u < last - h / 10.0 ? h / 25.0 : -h / 25.0);
                        }
                    }
                }
                return u;
            };
            const double ranges[][2] = {
                {away(first + 0.137 * h), away(first + 0.781 * h)},  // ends inside spans
                {k1, away(first + 0.9 * h)},                         // a at a knot
                {away(first + 0.05 * h), k2},                        // b at a knot
                {k1, k2},                                            // both at knots
                {first, last},                                       // the whole domain
                {k1 + 0.2 * span, k1 + 0.7 * span},                  // inside one span
            };
            double worst = 0.0;
            double left = 0.0;
            int same_structure = 0;
            double pole_gap = 0.0;
            for (const auto& range : ranges) {
                const Curve piece = c.ours.segment(range[0], range[1]);
                Handle(Geom_BSplineCurve) theirs = Handle(Geom_BSplineCurve)::DownCast(c.occ->Copy());
                theirs->Segment(range[0], range[1]);
                const JetComparison e = compare_jets(piece, theirs, rng, options.quick ? 20 : 80);
                worst = std::max(worst, e.worst());
                left = std::max(left, e.left);
                // Same knots, poles and weights (weights up to a common factor)?
                const std::vector<double> knots = piece.knots();
                const TColStd_Array1OfReal& sequence = theirs->KnotSequence();
                bool same = !theirs->IsPeriodic() && static_cast<int>(knots.size()) == sequence.Length() &&
                            static_cast<int>(piece.pole_count()) == theirs->NbPoles();
                for (std::size_t i = 0; same && i < knots.size(); ++i) {
                    same = std::abs(knots[i] - sequence(sequence.Lower() + static_cast<int>(i))) <=
                           1e-14 * std::max(1.0, std::abs(knots[i]));
                }
                if (same) {
                    ++same_structure;
                    const std::vector<double> points = piece.points();
                    const std::vector<double> weights = piece.weights();
                    for (int i = 1; i <= theirs->NbPoles(); ++i) {
                        const gp_Pnt mine = point3(&points[(i - 1) * c.dim], c.dim);
                        pole_gap = std::max(pole_gap, mine.Distance(theirs->Pole(i)));
                        pole_gap = std::max(pole_gap, std::abs(weights[i - 1] / weights[0] -
                                                               theirs->Weight(i) / theirs->Weight(1)));
                    }
                }
            }
            // A piece ending 1e-4 h past a knot has a last span that short:
            // its poles there nearly coincide, and any double-precision poles
            // give C'' and C''' on that span to about eps / span^2 and
            // eps / span^3 only (a property of the piece, not of either
            // library). Both pieces are compared with the curve they were cut
            // from (OCCT's, on its own long span): INFO row below.
            const double b_short = k2 + 1e-4 * h;
            const Curve short_piece = c.ours.segment(k1, b_short);
            Handle(Geom_BSplineCurve) short_theirs = Handle(Geom_BSplineCurve)::DownCast(c.occ->Copy());
            short_theirs->Segment(k1, b_short);
            const JetComparison e = compare_jets(short_piece, short_theirs, rng, options.quick ? 20 : 80, c.occ);
            double short_worst = e.left;
            for (int k = 0; k <= 3; ++k) {
                short_worst = std::max(short_worst, e.error[k]);
                short_ours[k] = std::max(short_ours[k], e.ours_ref[k]);
                short_occt[k] = std::max(short_occt[k], e.occt_ref[k]);
            }
            short_between = std::max(short_between, short_worst);
            report.row(worst <= tolerance, name, worst, tolerance,
                       format("6 ranges (ends inside spans, at knots, whole, inside a span): value + C' C'' "
                              "C''' at both ends, knots, random u; left of knots %.1e; knots/poles/weights as "
                              "OCCT's in %d of 6 (poles within %.1e)",
                              left, same_structure, pole_gap));
        });
    }
    report.info("n.segment-1e-4-end-span",
                format("the %zu curves cut at [k1, k_last + 1e-4 h]: ours vs OCCT's Segment %.1e; vs the uncut "
                       "curve, orders 0-3: ours %.1e %.1e %.1e %.1e, OCCT %.1e %.1e %.1e %.1e (both limited by "
                       "the 1e-4 span's conditioning, about eps / span^k)",
                       cases.size(), short_between, short_ours[0], short_ours[1], short_ours[2], short_ours[3],
                       short_occt[0], short_occt[1], short_occt[2], short_occt[3]));
    // Timing: a rational quintic (C^4) evaluated with 3 derivatives.
    guarded(report, "timing.nurbs-eval", [&] {
        std::mt19937_64 local(99);
        std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
        std::uniform_real_distribution<double> weight(0.3, 3.0);
        const int degree = 5;
        const int spans = 6;
        const int poles = spans + degree;
        TColgp_Array1OfPnt p(1, poles);
        TColStd_Array1OfReal w(1, poles);
        for (int i = 1; i <= poles; ++i) {
            p(i) = gp_Pnt(coordinate(local), coordinate(local), coordinate(local));
            w(i) = weight(local);
        }
        std::vector<double> knots;
        std::vector<int> mults;
        for (int i = 0; i <= spans; ++i) {
            knots.push_back(i * 0.5);
            mults.push_back(i == 0 || i == spans ? degree + 1 : 1);
        }
        const Handle(Geom_BSplineCurve) occ =
            new Geom_BSplineCurve(p, w, occ_reals(knots), occ_ints(mults), degree);
        const Curve ours = ours_from_occ(occ, 3);
        std::vector<double> params(1024);
        for (std::size_t i = 0; i < params.size(); ++i) {
            const double f = i * 0.6180339887498949 - std::floor(i * 0.6180339887498949);
            params[i] = 3.0 * f;
        }
        double buffer[12];
        gp_Pnt point;
        gp_Vec d1;
        gp_Vec d2;
        gp_Vec d3;
        const int batches = options.quick ? 1 : 15;
        const int calls = options.quick ? 10 : 50000;
        const Pair pair = time_pair(
            batches, calls,
            [&](int i) {
                ours.eval_into(params[i & 1023], 3, buffer, 12);
                g_sink = g_sink + buffer[9];
            },
            calls,
            [&](int i) {
                occ->D3(params[i & 1023], point, d1, d2, d3);
                g_sink = g_sink + d3.X();
            });
        timings.push_back({"NURBS eval + 3 derivatives (rational deg 5 3D)", "bzj_curve_eval order 3",
                           "Geom_BSplineCurve::D3", pair});
    });
}

// 3. bzj_nurbs_ellipse_arc against OCCT's ellipse (GC_MakeArcOfEllipse; a
// full turn against GC_MakeCircle / Geom_Ellipse): end points, the points and
// tangent directions at our knots (at the spans' angles) against OCCT's at
// those angles, and 1000 points between on OCCT's ellipse (implicit equation
// in OCCT's frame, first-order distance) within its arc and in its sense.
void check_ellipse(Report& report, const Options& options) {
    const double pi = 3.14159265358979323846;
    const double tolerance = 1e-12;
    struct Spec {
        const char* name;
        std::size_t dim;
        double centre[3];
        double tilt;   // rotation of the frame about (1, 1, 1)/sqrt(3) (3D) or about z (2D)
        double rx, ry;
        double a0, a1;
    };
    const Spec specs[] = {
        {"3D tilted rx>ry 3 spans", 3, {1.0, -2.0, 0.5}, 0.7, 3.0, 1.2, 0.3, 4.0},
        {"2D rx<ry 2 spans", 2, {-0.5, 0.25, 0.0}, 0.4, 0.8, 2.0, -2.5, 0.4},
        {"3D short 1 span", 3, {0.0, 0.0, 0.0}, -1.1, 2.0, 1.0, 5.0, 5.1},
        {"3D full circle", 3, {2.0, 1.0, -1.0}, 0.3, 1.5, 1.5, 0.7, 0.7 + 2.0 * pi},
        {"2D full ellipse", 2, {0.0, 0.0, 0.0}, 0.0, 1.0, 0.25, -pi, pi},
    };
    for (const Spec& s : specs) {
        const std::string name = format("n.ellipse[%s]", s.name);
        guarded(report, name, [&] {
            // An orthonormal frame X, Y (2D: in the plane).
            gp_Dir x_dir(1.0, 0.0, 0.0);
            gp_Dir y_dir(0.0, 1.0, 0.0);
            const gp_Ax1 axis = s.dim == 3 ? gp_Ax1(gp::Origin(), gp_Dir(1.0, 1.0, 1.0)) : gp::OZ();
            x_dir.Rotate(axis, s.tilt);
            y_dir.Rotate(axis, s.tilt);
            const std::size_t d = s.dim;
            const std::vector<double> centre(s.centre, s.centre + d);
            const std::vector<double> xv = {x_dir.X(), x_dir.Y(), x_dir.Z()};
            const std::vector<double> yv = {y_dir.X(), y_dir.Y(), y_dir.Z()};
            const Curve ours = Curve::ellipse_arc(d, centre, std::vector<double>(xv.begin(), xv.begin() + d),
                                                  std::vector<double>(yv.begin(), yv.begin() + d), s.rx, s.ry,
                                                  s.a0, s.a1);
            // OCCT's ellipse: major axis along X if rx >= ry, else along Y
            // (then OCCT's angle is ours - pi/2).
            const gp_Pnt c(s.centre[0], s.centre[1], s.centre[2]);
            const gp_Dir normal = x_dir.Crossed(y_dir);
            const bool swap = s.rx < s.ry;
            const double shift = swap ? -pi / 2.0 : 0.0;
            const gp_Elips elips(gp_Ax2(c, normal, swap ? y_dir : x_dir), std::max(s.rx, s.ry),
                                 std::min(s.rx, s.ry));
            const bool full = s.a1 - s.a0 >= 2.0 * pi;
            Handle(Geom_Curve) occ;
            if (full && s.rx == s.ry) {
                occ = GC_MakeCircle(gp_Circ(gp_Ax2(c, normal, x_dir), s.rx)).Value();
            } else if (full) {
                occ = new Geom_Ellipse(elips);
            } else {
                occ = GC_MakeArcOfEllipse(elips, s.a0 + shift, s.a1 + shift, true).Value();
            }
            // OCCT's parameter of our angle a: its first parameter + (a - a0).
            const double occ_first = full ? s.a0 + shift : occ->FirstParameter();
            const double radius = std::max(s.rx, s.ry);
            double ends = 0.0;
            const std::vector<double> start = ours.eval(s.a0);
            const std::vector<double> end = ours.eval(s.a1);
            ends = std::max(point3(start.data(), d).Distance(occ->Value(occ_first)),
                            point3(end.data(), d).Distance(occ->Value(occ_first + (s.a1 - s.a0)))) /
                   radius;
            if (!full) {
                ends = std::max(ends, std::abs((occ->LastParameter() - occ->FirstParameter()) - (s.a1 - s.a0)));
            }
            // Knots at the spans' angles: points and tangent directions.
            std::vector<double> knots;
            std::vector<int> mults;
            distinct_knots(ours.knots(), knots, mults);
            const std::size_t spans_expected =
                static_cast<std::size_t>(std::ceil((s.a1 - s.a0) / (pi / 2.0) - 1e-12));
            bool structure = knots.size() == spans_expected + 1 && ours.degree() == 2 && ours.is_rational();
            double at_knots = 0.0;
            double tangents = 0.0;
            for (std::size_t i = 0; i < knots.size(); ++i) {
                const double a = s.a0 + (s.a1 - s.a0) * static_cast<double>(i) / static_cast<double>(knots.size() - 1);
                at_knots = std::max(at_knots, std::abs(knots[i] - a) / std::max(1.0, std::abs(a)));
                const std::vector<double> jet = ours.eval(knots[i], 1);
                gp_Pnt point;
                gp_Vec tangent;
                occ->D1(occ_first + (knots[i] - s.a0), point, tangent);
                at_knots = std::max(at_knots, point3(jet.data(), d).Distance(point) / radius);
                const gp_Vec mine = jet_row(jet, 1, d);
                const double sine = mine.Crossed(tangent).Magnitude() / (mine.Magnitude() * tangent.Magnitude());
                tangents = std::max(tangents, mine.Dot(tangent) > 0.0 ? sine : INFINITY);
            }
            // Points between the knots: on OCCT's ellipse, on its arc, in its sense.
            const gp_Ax2 frame = elips.Position();
            const double a = elips.MajorRadius();
            const double b = elips.MinorRadius();
            double on = 0.0;
            double projected = 0.0;
            double previous = -INFINITY;
            bool monotone = true;
            const int samples = options.quick ? 100 : 1000;
            for (int i = 0; i <= samples; ++i) {
                const double u = s.a0 + (s.a1 - s.a0) * i / samples;
                const gp_Vec v(c, point3(ours.eval(u).data(), d));
                const double x = v.Dot(gp_Vec(frame.XDirection()));
                const double y = v.Dot(gp_Vec(frame.YDirection()));
                const double z = v.Dot(gp_Vec(frame.Direction()));
                const double f = (x / a) * (x / a) + (y / b) * (y / b) - 1.0;
                const double gradient = 2.0 * std::hypot(x / (a * a), y / (b * b));
                on = std::max(on, (std::abs(f) / gradient + std::abs(z)) / radius);
                // OCCT's angle of the point, unwrapped from its first parameter.
                double angle = std::atan2(y / b, x / a);
                angle += 2.0 * pi * std::round((occ_first + (u - s.a0) - angle) / (2.0 * pi));
                const bool inside = angle >= occ_first - 1e-9 && angle <= occ_first + (s.a1 - s.a0) + 1e-9;
                monotone = monotone && inside && angle >= previous;
                previous = angle;
                if (i % 10 == 5) {  // OCCT's own projection on a tenth of them
                    GeomAPI_ProjectPointOnCurve projection(point3(ours.eval(u).data(), d), occ);
                    projected = std::max(projected, projection.NbPoints() > 0 ? projection.LowerDistance() / radius
                                                                             : INFINITY);
                }
            }
            const double worst = std::max({ends, at_knots, tangents, on});
            const bool pass = structure && monotone && worst <= tolerance && projected <= 1e-9;
            report.row(pass, name, worst, tolerance,
                       format("vs %s: ends %.1e, %zu knots at the span angles %.1e, tangent angle %.1e, "
                              "%d points on the ellipse %.1e, in its arc and sense: %s; OCCT projection "
                              "distance %.1e (tol 1e-9)",
                              full ? (s.rx == s.ry ? "GC_MakeCircle" : "Geom_Ellipse") : "GC_MakeArcOfEllipse",
                              ends, knots.size(), at_knots, tangents, samples + 1, on, monotone ? "yes" : "NO",
                              projected));
        });
    }
}

// ---------------------------------------------------------------- one B-spline from fillet pieces

// Binomial coefficient as a double.
double binomial(int n, int k) {
    double out = 1.0;
    for (int i = 1; i <= k; ++i) {
        out = out * (n - k + i) / i;
    }
    return out;
}

// d^j w / du^j, j = 0..order, of a NURBS curve's weight function (the
// B-spline with the weights as coefficients) at u, by OCCT: the last span at
// the end of the domain, else the right side.
std::vector<double> weight_jet(const Curve& c, double u, int order) {
    std::vector<double> knots;
    std::vector<int> mults;
    distinct_knots(c.knots(), knots, mults);
    const std::vector<double> weights = c.weights();
    TColgp_Array1OfPnt poles(1, static_cast<int>(weights.size()));
    for (std::size_t i = 0; i < weights.size(); ++i) {
        poles(static_cast<int>(i) + 1) = gp_Pnt(weights[i], 0.0, 0.0);
    }
    const Handle(Geom_BSplineCurve) w =
        new Geom_BSplineCurve(poles, occ_reals(knots), occ_ints(mults), static_cast<int>(c.degree()));
    const int n = w->NbKnots();
    const bool at_end = u >= w->LastParameter();
    std::vector<double> out;
    out.push_back(at_end ? weights.back() : (u <= w->FirstParameter() ? weights.front() : w->Value(u).X()));
    for (int j = 1; j <= order; ++j) {
        out.push_back(at_end ? w->LocalDN(u, n - 1, n, j).X() : w->DN(u, j).X());
    }
    return out;
}

// One piece of a chain: a curve and the chain interval [s0, s1] its domain is
// mapped onto linearly.
struct ChainPiece {
    const Curve* curve;
    double s0;
    double s1;
};

// P_trim, R, Q_trim as ONE Geom_BSplineCurve on the given knot intervals, for
// RemoveKnot to judge the joins. Each piece is mapped linearly onto its
// interval (same poles and weights, mapped knots), raised to the common
// degree (IncreaseDegree) and the clamped pieces are concatenated (join knot
// multiplicity = degree, one shared pole: the left piece's; `pole_gap` is the
// C^0 defect, relative to the size).
//
// RemoveKnot works on the homogeneous curve (w C, w): a Cartesian C^k join of a
// rational piece with a polynomial blend is not a homogeneous C^k join. So when
// a neighbour is rational, the blend R (a Bezier curve) is written exactly as
// the rational curve (W R, W) with the polynomial W of degree (j_left + j_right
// + 1) whose derivatives 0..j at each end are the neighbour's weight function's
// (in the chain's parameter), j = k + 1: then the homogeneous chain is C^m at a
// join exactly when the Cartesian chain is, for every m <= k + 1. `blend_gap`
// measures that this re-representation is still R (relative, at 21 points).
struct RationalChain {
    Chain chain;
    std::vector<int> joins;  // 1-based indices of the join knots in chain.curve
    double blend_gap = 0.0;
    int blend_weight_degree = 0;
};

RationalChain make_rational_chain(const std::vector<ChainPiece>& pieces, std::size_t blend, int left_order,
                                  int right_order) {
    RationalChain out;
    const std::size_t dim = pieces.front().curve->dim();
    std::vector<Handle(Geom_BSplineCurve)> occ;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
        const Curve& c = *pieces[p].curve;
        std::vector<double> flat = c.knots();
        const std::pair<double, double> domain = c.domain();
        const double factor = (pieces[p].s1 - pieces[p].s0) / (domain.second - domain.first);
        for (double& k : flat) {
            k = k == domain.first ? pieces[p].s0
                                  : (k == domain.second ? pieces[p].s1 : pieces[p].s0 + (k - domain.first) * factor);
        }
        std::vector<double> knots;
        std::vector<int> mults;
        distinct_knots(flat, knots, mults);
        std::vector<double> points = c.points();
        std::vector<double> weights = c.weights();
        int degree = static_cast<int>(c.degree());
        if (p == blend) {
            const Curve* left = pieces[p - 1].curve;
            const Curve* right = pieces[p + 1].curve;
            if (left->is_rational() || right->is_rational()) {
                // Weight jets of the neighbours in R's own parameter t:
                // d/dt = (s1 - s0) d/ds, d/ds = (du/ds) d/du on a neighbour.
                const double length = pieces[p].s1 - pieces[p].s0;
                auto jet = [&](const ChainPiece& piece, bool at_end, int order) {
                    const std::pair<double, double> d = piece.curve->domain();
                    const double du_ds = (d.second - d.first) / (piece.s1 - piece.s0);
                    std::vector<double> w = weight_jet(*piece.curve, at_end ? d.second : d.first, order);
                    for (std::size_t j = 0; j < w.size(); ++j) {
                        w[j] *= std::pow(length * du_ds, static_cast<double>(j));
                    }
                    return w;
                };
                const std::vector<double> w0 = jet(pieces[p - 1], true, left_order);
                const std::vector<double> w1 = jet(pieces[p + 1], false, right_order);
                const int m = left_order + right_order + 1;
                // Bernstein coefficients of W from its end derivatives.
                std::vector<double> b(static_cast<std::size_t>(m) + 1, 0.0);
                for (int j = 0; j <= left_order; ++j) {
                    double sum = 0.0;
                    for (int i = 0; i < j; ++i) {
                        sum += ((j - i) % 2 ? -1.0 : 1.0) * binomial(j, i) * b[static_cast<std::size_t>(i)];
                    }
                    double falling = 1.0;  // m! / (m - j)!
                    for (int i = 0; i < j; ++i) {
                        falling *= m - i;
                    }
                    b[static_cast<std::size_t>(j)] = w0[static_cast<std::size_t>(j)] / falling - sum;
                }
                for (int j = 0; j <= right_order; ++j) {
                    // W^(j)(1) = m!/(m-j)! sum_i (-1)^(j-i) C(j,i) b[m-j+i]
                    double sum = 0.0;
                    for (int i = 1; i <= j; ++i) {
                        sum += ((j - i) % 2 ? -1.0 : 1.0) * binomial(j, i) * b[static_cast<std::size_t>(m - j + i)];
                    }
                    double falling = 1.0;
                    for (int i = 0; i < j; ++i) {
                        falling *= m - i;
                    }
                    b[static_cast<std::size_t>(m - j)] = (w1[static_cast<std::size_t>(j)] / falling - sum) * (j % 2 ? -1.0 : 1.0);
                }
                // (W R, W) in degree n + m.
                const int n = degree;
                std::vector<double> new_points;
                std::vector<double> new_weights;
                for (int k = 0; k <= n + m; ++k) {
                    std::vector<double> numerator(dim, 0.0);
                    double denominator = 0.0;
                    for (int i = std::max(0, k - n); i <= std::min(m, k); ++i) {
                        const int j = k - i;
                        const double f = binomial(m, i) * binomial(n, j) / binomial(n + m, k) *
                                         b[static_cast<std::size_t>(i)];
                        denominator += f;
                        for (std::size_t c2 = 0; c2 < dim; ++c2) {
                            numerator[c2] += f * points[static_cast<std::size_t>(j) * dim + c2];
                        }
                    }
                    if (!(denominator > 0.0)) {
                        throw std::runtime_error(format("judge: the blend's weight polynomial has a weight %.3e <= 0",
                                                        denominator));
                    }
                    for (double x : numerator) {
                        new_points.push_back(x / denominator);
                    }
                    new_weights.push_back(denominator);
                }
                points = new_points;
                weights = new_weights;
                degree = n + m;
                mults.front() = degree + 1;
                mults.back() = degree + 1;
                out.blend_weight_degree = m;
            }
        }
        occ.push_back(new Geom_BSplineCurve(poles3(points, dim), occ_reals(weights), occ_reals(knots),
                                            occ_ints(mults), degree));
        if (p == blend) {
            // The re-representation is still R.
            for (int i = 0; i <= 20; ++i) {
                const double t = i / 20.0;
                const gp_Pnt theirs = occ.back()->Value(pieces[p].s0 + t * (pieces[p].s1 - pieces[p].s0));
                const gp_Pnt mine = point3(c.eval(t).data(), dim);
                out.blend_gap = std::max(out.blend_gap, theirs.Distance(mine) / std::max(1.0, gp_Vec(mine.XYZ()).Magnitude()));
            }
        }
    }
    int degree = 0;
    for (const auto& c : occ) {
        degree = std::max(degree, c->Degree());
    }
    if (degree > Geom_BSplineCurve::MaxDegree()) {
        throw std::runtime_error(format("judge: chain degree %d above OCCT's %d", degree,
                                        Geom_BSplineCurve::MaxDegree()));
    }
    std::vector<gp_Pnt> poles;
    std::vector<double> weights;
    std::vector<double> knots;
    std::vector<int> mults;
    Chain& chain = out.chain;
    chain.degree = degree;
    for (std::size_t p = 0; p < occ.size(); ++p) {
        const Handle(Geom_BSplineCurve)& c = occ[p];
        c->IncreaseDegree(degree);
        if (c->Multiplicity(1) != degree + 1 || c->Multiplicity(c->NbKnots()) != degree + 1) {
            throw std::runtime_error(format("judge: piece %zu is not clamped (end multiplicities %d, %d)", p,
                                            c->Multiplicity(1), c->Multiplicity(c->NbKnots())));
        }
        for (int i = 1; i <= c->NbPoles(); ++i) {
            const gp_Pnt pole = c->Pole(i);
            chain.size = std::max({chain.size, std::abs(pole.X()), std::abs(pole.Y()), std::abs(pole.Z())});
            if (p > 0 && i == 1) {
                chain.pole_gap = std::max(chain.pole_gap, pole.Distance(poles.back()));
                chain.pole_gap = std::max(chain.pole_gap, std::abs(c->Weight(1) - weights.back()) / weights.back());
                continue;
            }
            poles.push_back(pole);
            weights.push_back(c->Weight(i));
        }
        for (int i = 1; i <= c->NbKnots(); ++i) {
            if (p > 0 && i == 1) {
                mults.back() = degree;
                out.joins.push_back(static_cast<int>(knots.size()));
                continue;
            }
            knots.push_back(c->Knot(i));
            mults.push_back(c->Multiplicity(i));
        }
    }
    chain.pole_gap /= chain.size;
    chain.knots = knots;
    TColgp_Array1OfPnt occ_poles(1, static_cast<int>(poles.size()));
    for (std::size_t i = 0; i < poles.size(); ++i) {
        occ_poles(static_cast<int>(i) + 1) = poles[i];
    }
    chain.curve = new Geom_BSplineCurve(occ_poles, occ_reals(weights), occ_reals(knots), occ_ints(mults), degree);
    return out;
}

// The verdict at one join: RemoveKnot to degree - k (C^k) must succeed and to
// degree - k - 1 (C^(k+1)) must fail (the guard that the judge can fail);
// the one-sided derivatives 0..k agree (jump) and those of order k + 1 do not
// (jump_next).
struct JoinResult {
    JoinVerdict verdict;
    double jump_next = 0.0;
};

JoinResult judge_rational_join(const Chain& chain, int index, int k, double tolerance) {
    JoinResult r;
    r.verdict = judge_join(chain, index, k, tolerance * chain.size);
    const double u = chain.knots[static_cast<std::size_t>(index) - 1];
    const gp_Vec left = chain.curve->LocalDN(u, index - 1, index, k + 1);
    const gp_Vec right = chain.curve->LocalDN(u, index, index + 1, k + 1);
    r.jump_next = (left - right).Magnitude() / std::max({1.0, left.Magnitude(), right.Magnitude()});
    return r;
}

// Trimmed piece `piece` (domain [a, b] of `whole`) against OCCT's
// Segment(a, b) of `whole`: relative jet error (orders 0..3).
double trim_error(const Curve& piece, const Curve& whole, std::mt19937_64& rng) {
    const std::pair<double, double> d = piece.domain();
    Handle(Geom_BSplineCurve) theirs = occ_bspline(whole);
    theirs->Segment(d.first, d.second);
    return compare_jets(piece, theirs, rng, 40).worst();
}

// One fillet row: the trims against OCCT's Segment, u0 / v0 against the
// setbacks by OCCT's arc length, and C^kp / C^kq at the two joins of the one
// B-spline P_trim, R, Q_trim (knot intervals (u0 - first, alpha,
// (last - v0) alpha / beta)) by RemoveKnot, with the C^(k+1) guard.
struct FilletJudgement {
    bool pass = false;
    double worst = 0.0;
    std::string note;
};

FilletJudgement judge_fillet(const Curve& p, const Curve& q, const bezjoin::Fillet& f,
                             const bezjoin::FilletOptions& opts, double u0_occt, double v0_occt,
                             std::mt19937_64& rng) {
    FilletJudgement j;
    const double tolerance = 1e-9;
    const std::pair<double, double> pd = f.p_trimmed.domain();
    const std::pair<double, double> qd = f.q_trimmed.domain();
    const double u0 = pd.second;
    const double v0 = qd.first;
    const bool kinds = f.p_trimmed.is_nurbs() == p.is_nurbs() && f.q_trimmed.is_nurbs() == q.is_nurbs() &&
                       !f.blend.is_nurbs() && pd.first == p.domain().first && qd.second == q.domain().second &&
                       f.blend.degree() == opts.p_order + opts.q_order + 1;
    const double cut = std::max(std::abs(u0 - u0_occt), std::abs(v0 - v0_occt));
    const double trims = std::max(trim_error(f.p_trimmed, p, rng), trim_error(f.q_trimmed, q, rng));
    const double alpha = opts.p_scale;
    const double beta = opts.q_scale;
    const double s1 = u0 + alpha;
    const double s2 = s1 + (qd.second - v0) * alpha / beta;
    const RationalChain rc = make_rational_chain({{&f.p_trimmed, pd.first, u0}, {&f.blend, u0, s1}, {&f.q_trimmed, s1, s2}},
                                                 1, static_cast<int>(opts.p_order) + 1,
                                                 static_cast<int>(opts.q_order) + 1);
    const int kp = static_cast<int>(opts.p_order);
    const int kq = static_cast<int>(opts.q_order);
    // The same joins by our own evaluation: R^(k)(0) = alpha^k P^(k)(u0-),
    // R^(k)(1) = beta^k Q^(k)(v0+) (relative to max(1, |P^(k)|)).
    double direct = 0.0;
    {
        const std::size_t dim = p.dim();
        const std::vector<double> pj = f.p_trimmed.eval(u0, opts.p_order);
        const std::vector<double> qj = f.q_trimmed.eval(v0, opts.q_order);
        const std::vector<double> r0 = f.blend.eval(0.0, opts.p_order);
        const std::vector<double> r1 = f.blend.eval(1.0, opts.q_order);
        for (int k = 0; k <= std::max(kp, kq); ++k) {
            if (k <= kp) {
                const gp_Vec a = jet_row(pj, static_cast<std::size_t>(k), dim) * std::pow(alpha, k);
                direct = std::max(direct, (jet_row(r0, static_cast<std::size_t>(k), dim) - a).Magnitude() /
                                              std::max(1.0, a.Magnitude()));
            }
            if (k <= kq) {
                const gp_Vec b = jet_row(qj, static_cast<std::size_t>(k), dim) * std::pow(beta, k);
                direct = std::max(direct, (jet_row(r1, static_cast<std::size_t>(k), dim) - b).Magnitude() /
                                              std::max(1.0, b.Magnitude()));
            }
        }
    }
    const JoinResult left = judge_rational_join(rc.chain, rc.joins[0], kp, tolerance);
    const JoinResult right = judge_rational_join(rc.chain, rc.joins[1], kq, tolerance);
    j.worst = std::max({cut, trims, rc.blend_gap, rc.chain.pole_gap, left.verdict.jump, right.verdict.jump});
    const bool judged = left.verdict.removable && right.verdict.removable;
    const bool guard = !left.verdict.stricter && !right.verdict.stricter;
    j.pass = kinds && judged && guard && j.worst <= tolerance && trims <= 1e-12;
    j.note = format("u0 %.9f v0 %.9f (vs OCCT arc length %.1e); trims vs Segment %.1e; one B-spline of degree %d%s: "
                    "RemoveKnot C^%d %s / C^%d %s, C^%d %s / C^%d %s (guard); jumps orders <=k %.1e, order k+1 "
                    "%.1e / %.1e; by our own eval: jump orders <=k %.1e",
                    u0, v0, cut, trims, rc.chain.degree,
                    rc.blend_weight_degree ? format(" (R rational, W of degree %d)", rc.blend_weight_degree).c_str() : "",
                    kp, left.verdict.removable ? "ok" : "REFUSED", kq, right.verdict.removable ? "ok" : "REFUSED",
                    kp + 1, left.verdict.stricter ? "ALSO OK" : "refused", kq + 1,
                    right.verdict.stricter ? "ALSO OK" : "refused", std::max(left.verdict.jump, right.verdict.jump),
                    left.jump_next, right.jump_next, direct);
    if (!kinds) {
        j.note += "; WRONG piece kinds/domains/blend degree";
    }
    return j;
}

// 4a. An arc (OCCT's GC_MakeArcOfCircle through GeomConvert, into
// bzj_nurbs_new) and a line (GeomConvert of a trimmed Geom_Line) meeting at a
// vertex, 4e-8 apart: bzj_fillet_vertex with gap 1e-7, C1, C2, C3 and an
// asymmetric scaled case. 4b. Two crossing B-spline edges (OCCT's
// GeomAPI_PointsToBSpline and explicit poles, one case rational) with
// bzj_fillet. 5. ChFi2d_FilletAPI on the same arc-line corner, timed.
void check_nurbs_fillets(Report& report, std::vector<Timing>& timings, const Options& options) {
    std::mt19937_64 rng(16005);
    const double pi = 3.14159265358979323846;
    // The corner: the unit circle's arc from -1.0 to 2.4 rad (GeomConvert
    // writes it in 2 rational quadratic spans on [2 pi - 1, 2 pi + 2.4]),
    // then a line turning 60 degrees to the right of the arc's end tangent.
    const double a_start = -1.0;
    const double a_end = 2.4;
    const gp_Pnt vertex(std::cos(a_end), std::sin(a_end), 0.0);
    const gp_Dir end_tangent(-std::sin(a_end), std::cos(a_end), 0.0);
    const gp_Dir line_dir = end_tangent.Rotated(gp::OZ(), -pi / 3.0);
    const double line_length = 2.0;
    const Handle(Geom_TrimmedCurve) arc_occ =
        GC_MakeArcOfCircle(gp_Circ(gp::XOY(), 1.0), a_start, a_end, true).Value();
    const Handle(Geom_BSplineCurve) arc_bspline = GeomConvert::CurveToBSplineCurve(arc_occ);
    const gp_Vec offset = gp_Vec(line_dir.Crossed(gp::DZ())) * 4e-8;  // the sketch's gap
    const Handle(Geom_TrimmedCurve) line_occ =
        new Geom_TrimmedCurve(new Geom_Line(vertex.Translated(offset), line_dir), 0.0, line_length);
    const Handle(Geom_BSplineCurve) line_bspline = GeomConvert::CurveToBSplineCurve(line_occ);
    Curve arc;
    Curve line;
    guarded(report, "n.fillet_vertex-inputs", [&] {
        arc = ours_from_occ(arc_bspline, 2);
        line = ours_from_occ(line_bspline, 2);
        report.info("n.fillet_vertex-inputs",
                    format("arc: GeomConvert of GC_MakeArcOfCircle, degree %d, rational %s, %s; line: degree %d, "
                           "domain [%g, %g]; vertex gap 4e-8",
                           arc_bspline->Degree(), arc_bspline->IsRational() ? "yes" : "no",
                           describe(arc_bspline).c_str(), line_bspline->Degree(), line_bspline->FirstParameter(),
                           line_bspline->LastParameter()));
    });
    if (!arc || !line) {
        return;
    }
    struct Case {
        const char* name;
        double dp, dq;
        std::size_t kp, kq;
        double alpha, beta;
    };
    const Case vertex_cases[] = {
        {"arc+line C1", 0.3, 0.3, 1, 1, 1.0, 1.0},
        {"arc+line C2", 0.3, 0.3, 2, 2, 1.0, 1.0},
        {"arc+line C3", 0.3, 0.3, 3, 3, 1.0, 1.0},
        {"arc+line C3/C2 scaled", 0.25, 0.4, 3, 2, 1.4, 0.7},
    };
    for (const Case& cs : vertex_cases) {
        const std::string name = format("n.fillet_vertex[%s]", cs.name);
        guarded(report, name, [&] {
            bezjoin::FilletOptions opts;
            opts.p_setback = cs.dp;
            opts.q_setback = cs.dq;
            opts.p_order = cs.kp;
            opts.q_order = cs.kq;
            opts.p_scale = cs.alpha;
            opts.q_scale = cs.beta;
            const bezjoin::Fillet f = bezjoin::fillet_vertex(arc, line, opts, 1e-7);
            const double u0 = GCPnts_AbscissaPoint(1e-13, GeomAdaptor_Curve(arc_bspline), -cs.dp,
                                                   arc_bspline->LastParameter()).Parameter();
            const double v0 = GCPnts_AbscissaPoint(1e-13, GeomAdaptor_Curve(line_bspline), cs.dq,
                                                   line_bspline->FirstParameter()).Parameter();
            const FilletJudgement j = judge_fillet(arc, line, f, opts, u0, v0, rng);
            report.row(j.pass, name, j.worst, 1e-9, j.note);
        });
    }
    expect_status(report, "n.fillet_vertex-gap-too-large", BZJ_ERR_NO_INTERSECTION, [&] {
        bezjoin::FilletOptions opts;
        opts.p_setback = 0.3;
        opts.q_setback = 0.3;
        opts.p_order = 2;
        opts.q_order = 2;
        (void)bezjoin::fillet_vertex(arc, line, opts, 1e-8);  // the ends are 4e-8 apart
    });

    // 4b. Two crossing B-spline edges.
    guarded(report, "n.fillet[bspline inputs]", [&] {
        TColgp_Array1OfPnt wave(1, 9);
        for (int i = 1; i <= 9; ++i) {
            const double x = -2.0 + 4.0 * (i - 1) / 8.0;
            wave(i) = gp_Pnt(x, 0.3 * std::sin(1.7 * x) - 0.05 * x, 0.0);
        }
        GeomAPI_PointsToBSpline fit(wave, 3, 3, GeomAbs_C2, 1e-6);
        if (!fit.IsDone()) {
            throw std::runtime_error("GeomAPI_PointsToBSpline failed");
        }
        const Handle(Geom_BSplineCurve) p_occ = fit.Curve();
        // Q: explicit quartic poles, a double interior knot, on [1, 4].
        TColgp_Array1OfPnt q_poles(1, 8);
        const double qp[8][2] = {{0.3, -2.0}, {0.5, -1.4}, {-0.2, -0.9}, {0.1, -0.3},
                                 {0.2, 0.4},  {-0.3, 0.9}, {0.1, 1.5},  {-0.1, 2.1}};
        for (int i = 1; i <= 8; ++i) {
            q_poles(i) = gp_Pnt(qp[i - 1][0], qp[i - 1][1], 0.0);
        }
        const Handle(Geom_BSplineCurve) q_occ =
            new Geom_BSplineCurve(q_poles, occ_reals({1.0, 2.2, 4.0}), occ_ints({5, 3, 5}), 4);
        Handle(Geom_BSplineCurve) q_rational = Handle(Geom_BSplineCurve)::DownCast(q_occ->Copy());
        const double weights[8] = {1.0, 1.6, 0.7, 1.2, 2.0, 0.8, 1.1, 0.9};
        for (int i = 1; i <= 8; ++i) {
            q_rational->SetWeight(i, weights[i - 1]);
        }
        const Curve p = ours_from_occ(p_occ, 2);
        report.info("n.fillet[bspline inputs]",
                    format("P: GeomAPI_PointsToBSpline of 9 points, degree %d, %s; Q: degree 4, %s, and a "
                           "rational copy (weights 0.7..2)",
                           p_occ->Degree(), describe(p_occ).c_str(), describe(q_occ).c_str()));
        struct BCase {
            const char* name;
            const Handle(Geom_BSplineCurve)* q;
            double dp, dq;
            std::size_t kp, kq;
            double alpha, beta;
        };
        const BCase cases[] = {
            {"bspline x bspline C2", &q_occ, 0.35, 0.35, 2, 2, 1.0, 1.0},
            {"bspline x bspline C3", &q_occ, 0.3, 0.4, 3, 3, 1.0, 1.0},
            {"bspline x rational C3/C2 scaled", &q_rational, 0.3, 0.3, 3, 2, 1.3, 0.8},
        };
        for (const BCase& cs : cases) {
            const std::string name = format("n.fillet[%s]", cs.name);
            guarded(report, name, [&] {
                const Curve q = ours_from_occ(*cs.q, 2);
                // OCCT's first crossing (smallest u on P) and ours.
                Geom2dAPI_InterCurveCurve inter(occ_bspline2d(p), occ_bspline2d(q), 1e-12);
                if (inter.NbPoints() < 1) {
                    throw std::runtime_error("OCCT finds no crossing");
                }
                double u_star = INFINITY;
                double v_star = 0.0;
                for (int i = 1; i <= inter.NbPoints(); ++i) {
                    const IntRes2d_IntersectionPoint& point = inter.Intersector().Point(i);
                    if (point.ParamOnFirst() < u_star) {
                        u_star = point.ParamOnFirst();
                        v_star = point.ParamOnSecond();
                    }
                }
                const auto ours_crossings = bezjoin::intersect(p, q);
                const double crossing_gap =
                    ours_crossings.empty() ? INFINITY
                                           : std::max(std::abs(ours_crossings.front().first - u_star),
                                                      std::abs(ours_crossings.front().second - v_star));
                bezjoin::FilletOptions opts;
                opts.p_setback = cs.dp;
                opts.q_setback = cs.dq;
                opts.p_order = cs.kp;
                opts.q_order = cs.kq;
                opts.p_scale = cs.alpha;
                opts.q_scale = cs.beta;
                const bezjoin::Fillet f = bezjoin::fillet(p, q, opts);
                const Handle(Geom_BSplineCurve) p3 = occ_bspline(p);
                const Handle(Geom_BSplineCurve) q3 = occ_bspline(q);
                const double u0 = GCPnts_AbscissaPoint(1e-13, GeomAdaptor_Curve(p3), -cs.dp, u_star).Parameter();
                const double v0 = GCPnts_AbscissaPoint(1e-13, GeomAdaptor_Curve(q3), cs.dq, v_star).Parameter();
                const FilletJudgement j = judge_fillet(p, q, f, opts, u0, v0, rng);
                const double worst = std::max(j.worst, crossing_gap);
                report.row(j.pass && crossing_gap <= 1e-10, name, worst, 1e-9,
                           format("crossing (u*, v*) = (%.9f, %.9f), ours - OCCT %.1e (%d by OCCT); %s", u_star,
                                  v_star, crossing_gap, inter.NbPoints(), j.note.c_str()));
            });
        }
    });

    // 5. ChFi2d_FilletAPI on the same arc-line corner (analytic edges: the
    // circle arc and the line, sharing the vertex), radius giving the same
    // 0.3 setback for a corner of straight edges with the same turn.
    guarded(report, "n.ChFi2d[arc+line]", [&] {
        const double turn = pi / 3.0;
        const double radius = 0.3 / std::tan(turn / 2.0);
        const gp_Pln plane(gp::XOY());
        auto build_edges = [&](TopoDS_Edge& e1, TopoDS_Edge& e2) {
            const TopoDS_Vertex start = BRepBuilderAPI_MakeVertex(arc_occ->StartPoint());
            const TopoDS_Vertex middle = BRepBuilderAPI_MakeVertex(vertex);
            const TopoDS_Vertex end = BRepBuilderAPI_MakeVertex(vertex.Translated(gp_Vec(line_dir) * line_length));
            e1 = BRepBuilderAPI_MakeEdge(arc_occ->BasisCurve(), start, middle, a_start, a_end).Edge();
            e2 = BRepBuilderAPI_MakeEdge(new Geom_Line(vertex, line_dir), middle, end, 0.0, line_length).Edge();
        };
        auto run_occt = [&](TopoDS_Edge& m1, TopoDS_Edge& m2) {
            TopoDS_Edge e1;
            TopoDS_Edge e2;
            build_edges(e1, e2);
            ChFi2d_FilletAPI api(e1, e2, plane);
            if (!api.Perform(radius) || api.NbResults(vertex) < 1) {
                throw std::runtime_error("ChFi2d_FilletAPI found no fillet");
            }
            return api.Result(vertex, m1, m2, -1);
        };
        TopoDS_Edge m1;
        TopoDS_Edge m2;
        const TopoDS_Edge fillet_edge = run_occt(m1, m2);
        double first = 0.0;
        double last = 0.0;
        const Handle(Geom_Curve) fillet_curve = BRep_Tool::Curve(fillet_edge, first, last);
        const Handle(Geom_Circle) circle = Handle(Geom_Circle)::DownCast(
            Handle(Geom_TrimmedCurve)::DownCast(fillet_curve).IsNull()
                ? fillet_curve
                : Handle(Geom_TrimmedCurve)::DownCast(fillet_curve)->BasisCurve());
        const gp_Pnt a = fillet_curve->Value(first);
        const gp_Pnt b = fillet_curve->Value(last);
        // Setbacks: distance of the tangency points from the vertex along
        // each edge (chords; the arc's is about its arc length).
        const double sa = std::min(a.Distance(vertex), b.Distance(vertex));
        const double sb = std::max(a.Distance(vertex), b.Distance(vertex));
        // Curvature jumps at the tangency points: OCCT's G1 arc against its
        // trimmed edges (each at its end nearer the arc), and ours (C3,
        // setbacks 0.3) between the pieces.
        double occt_jump = 0.0;
        for (const TopoDS_Edge* edge : {&m1, &m2}) {
            double e_first = 0.0;
            double e_last = 0.0;
            const Handle(Geom_Curve) curve = BRep_Tool::Curve(*edge, e_first, e_last);
            const double da = std::min(curve->Value(e_first).Distance(a), curve->Value(e_first).Distance(b));
            const double db = std::min(curve->Value(e_last).Distance(a), curve->Value(e_last).Distance(b));
            const double u_edge = da < db ? e_first : e_last;
            const gp_Pnt at = curve->Value(u_edge);
            const double u_arc = at.Distance(a) < at.Distance(b) ? first : last;
            occt_jump = std::max(occt_jump, std::abs(curvature(curve, u_edge) - curvature(fillet_curve, u_arc)));
        }
        bezjoin::FilletOptions opts;
        opts.p_setback = 0.3;
        opts.q_setback = 0.3;
        opts.p_order = 3;
        opts.q_order = 3;
        const bezjoin::Fillet f = bezjoin::fillet_vertex(arc, line, opts, 1e-7);
        const double u0 = f.p_trimmed.domain().second;
        const double v0 = f.q_trimmed.domain().first;
        const double our_jump = std::max(std::abs(curvature(f.p_trimmed, u0) - curvature(f.blend, 0.0)),
                                         std::abs(curvature(f.blend, 1.0) - curvature(f.q_trimmed, v0)));
        const double radius_gap = circle.IsNull() ? INFINITY : std::abs(circle->Radius() - radius) / radius;
        report.row(radius_gap <= 1e-9, "n.ChFi2d[arc+line]", radius_gap, 1e-9,
                   format("OCCT's fillet is a circle of radius %.6f (asked %.6f); tangency points %.4f / %.4f "
                          "from the vertex; curvature jump at the tangency points: OCCT (G1 arc) %.3f, ours "
                          "(C3) %.1e",
                          circle.IsNull() ? NAN : circle->Radius(), radius, sa, sb, occt_jump, our_jump));
        const Pair pair = time_pair(
            options.quick ? 1 : 9, options.quick ? 1 : 500,
            [&](int) {
                const bezjoin::Fillet again = bezjoin::fillet_vertex(arc, line, opts, 1e-7);
                g_sink = g_sink + static_cast<double>(again.blend.degree());
            },
            options.quick ? 1 : 500,
            [&](int) {
                TopoDS_Edge x;
                TopoDS_Edge y;
                const TopoDS_Edge result = run_occt(x, y);
                g_sink = g_sink + static_cast<double>(result.IsNull());
            });
        timings.push_back({"fillet arc + line at a vertex (ours C3, OCCT G1)", "bzj_fillet_vertex C3",
                           "2 edges + ChFi2d_FilletAPI", pair});
        // Where OCCT's time goes.
        const int batches = options.quick ? 1 : 7;
        const int calls = options.quick ? 1 : 300;
        TopoDS_Edge e1;
        TopoDS_Edge e2;
        build_edges(e1, e2);
        const double edges_ns = time_per_call_ns(batches, calls, [&](int) {
            TopoDS_Edge x;
            TopoDS_Edge y;
            build_edges(x, y);
            g_sink = g_sink + static_cast<double>(x.IsNull());
        });
        const double api_ns = time_per_call_ns(batches, calls, [&](int) {
            ChFi2d_FilletAPI api(e1, e2, plane);
            TopoDS_Edge x;
            TopoDS_Edge y;
            const bool done = api.Perform(radius) && api.NbResults(vertex) > 0;
            g_sink = g_sink + static_cast<double>(done ? api.Result(vertex, x, y, -1).IsNull() : 1);
        });
        const double ana_ns = time_per_call_ns(batches, calls, [&](int) {
            ChFi2d_AnaFilletAlgo algo(e1, e2, plane);
            TopoDS_Edge x;
            TopoDS_Edge y;
            const bool done = algo.Perform(radius);
            g_sink = g_sink + static_cast<double>(done ? algo.Result(x, y).IsNull() : 1);
        });
        report.info("n.ChFi2d[arc+line]-time-split",
                    format("OCCT: building the 2 edges %s, ChFi2d_FilletAPI on built edges %s (it picks the "
                           "analytic algorithm for a line and an arc), ChFi2d_AnaFilletAlgo itself %s%s",
                           format_time(edges_ns).c_str(), format_time(api_ns).c_str(), format_time(ana_ns).c_str(),
                           options.quick ? " [quick run: not meaningful]" : ""));
    });
}

// d. fillet: our crossing vs Geom2dAPI_InterCurveCurve, setbacks by OCCT's
// arc length, continuity as in c, and OCCT's circular fillet of the same corner.
void check_fillet(Report& report, StepScene& scene, std::vector<Timing>& timings,
                  const Options& options) {
    const Curve p(2, 3, {0.0, 0.0, 0.8, 0.3, 1.5, -0.2, 2.2, 0.4});
    const Curve q(2, 3, {1.0, -1.0, 1.3, -0.2, 0.8, 0.6, 1.2, 1.4});
    double u_star = 0.0;
    double v_star = 0.0;
    guarded(report, "d.intersect-vs-InterCurveCurve", [&] {
        const auto ours = bezjoin::intersect(p, q);
        Geom2dAPI_InterCurveCurve occ(occ_bezier2d(p), occ_bezier2d(q), 1e-12);
        const Geom2dInt_GInter& inter = occ.Intersector();
        double worst = 0.0;
        bool pass = static_cast<int>(ours.size()) == occ.NbPoints() && !ours.empty();
        for (const auto& uv : ours) {
            double best = INFINITY;
            for (int i = 1; i <= occ.NbPoints(); ++i) {
                const IntRes2d_IntersectionPoint& point = inter.Point(i);
                best = std::min(best, std::max(std::abs(point.ParamOnFirst() - uv.first),
                                               std::abs(point.ParamOnSecond() - uv.second)));
            }
            worst = std::max(worst, best);
        }
        if (!ours.empty()) {
            u_star = ours.front().first;
            v_star = ours.front().second;
            const std::vector<double> a = p.eval(u_star);
            const std::vector<double> b = q.eval(v_star);
            worst = std::max(worst, std::hypot(a[0] - b[0], a[1] - b[1]));
        }
        pass = pass && worst <= 1e-10;
        report.row(pass, "d.intersect-vs-InterCurveCurve", worst, 1e-10,
                   format("ours %zu crossing(s), OCCT %d; (u*, v*) = (%.12f, %.12f); "
                          "worst of |du|, |dv|, |P(u*)-Q(v*)|",
                          ours.size(), occ.NbPoints(), u_star, v_star));
    });
    if (u_star == 0.0) {
        return;
    }

    struct Case {
        const char* name;
        double dp, dq;
        std::size_t kp, kq;
        double alpha, beta;
    };
    const Case cases[] = {
        {"C3 symmetric", 0.3, 0.3, 3, 3, 1.0, 1.0},
        {"C2 asymmetric scaled", 0.25, 0.4, 2, 2, 1.2, 0.8},
    };
    const Handle(Geom2d_BezierCurve) occ_p2 = occ_bezier2d(p);
    const Handle(Geom2d_BezierCurve) occ_q2 = occ_bezier2d(q);
    const double tolerance = 1e-9;
    double our_jump = 0.0;
    for (const Case& cs : cases) {
        const std::string name = format("d.fillet[%s]", cs.name);
        guarded(report, name, [&] {
            bezjoin::FilletOptions opts;
            opts.p_setback = cs.dp;
            opts.q_setback = cs.dq;
            opts.p_order = cs.kp;
            opts.q_order = cs.kq;
            opts.p_scale = cs.alpha;
            opts.q_scale = cs.beta;
            const bezjoin::Fillet f = bezjoin::fillet(p, q, opts);
            // u0, v0 from the setbacks by OCCT's own arc length.
            const double u0 = GCPnts_AbscissaPoint(1e-13, Geom2dAdaptor_Curve(occ_p2), -cs.dp, u_star).Parameter();
            const double v0 = GCPnts_AbscissaPoint(1e-13, Geom2dAdaptor_Curve(occ_q2), cs.dq, v_star).Parameter();
            const double trim_gap = std::max(
                pole_difference(f.p_trimmed, occ_segment(occ_bezier(p), 0.0, u0)),
                pole_difference(f.q_trimmed, occ_segment(occ_bezier(q), v0, 1.0)));
            const Chain chain = make_chain({&f.p_trimmed, &f.blend, &f.q_trimmed},
                                           {u0, cs.alpha, (1.0 - v0) * cs.alpha / cs.beta});
            const JoinVerdict left = judge_join(chain, 2, static_cast<int>(cs.kp), tolerance * chain.size);
            const JoinVerdict right = judge_join(chain, 3, static_cast<int>(cs.kq), tolerance * chain.size);
            const double worst = std::max({left.jump, right.jump, chain.pole_gap, trim_gap});
            const bool pass = left.removable && right.removable && worst <= tolerance;
            report.row(pass, name, worst, tolerance,
                       format("u0 = %.6f v0 = %.6f (OCCT arc length); trims vs Segment %.1e; "
                              "RemoveKnot C^%zu: %s, C^%zu: %s",
                              u0, v0, trim_gap, cs.kp, left.removable ? "ok" : "REFUSED", cs.kq,
                              right.removable ? "ok" : "REFUSED"));
            if (cs.kp == 3) {
                our_jump = std::max(
                    std::abs(curvature(f.p_trimmed, 1.0) - curvature(f.blend, 0.0)),
                    std::abs(curvature(f.blend, 1.0) - curvature(f.q_trimmed, 0.0)));
                scene.add(f.p_trimmed, gp_Vec(0.0, 3.0, 0.0));
                scene.add(f.blend, gp_Vec(0.0, 3.0, 0.0));
                scene.add(f.q_trimmed, gp_Vec(0.0, 3.0, 0.0));
            }
        });
    }

    // OCCT's circular fillet of the same corner, radius giving about the same
    // setback (0.3) for the tangent directions at the crossing.
    guarded(report, "d.ChFi2d_FilletAPI", [&] {
        const Handle(Geom_BezierCurve) occ_p = occ_bezier(p);
        const Handle(Geom_BezierCurve) occ_q = occ_bezier(q);
        const gp_Pnt corner = occ_p->Value(u_star);
        const gp_Vec tp = occ_p->DN(u_star, 1).Normalized();
        const gp_Vec tq = occ_q->DN(v_star, 1).Normalized();
        const double turn = tp.Angle(tq);
        const double radius = 0.3 / std::tan(turn / 2.0);
        const TopoDS_Vertex start = BRepBuilderAPI_MakeVertex(occ_p->Value(0.0));
        const TopoDS_Vertex middle = BRepBuilderAPI_MakeVertex(corner);
        const TopoDS_Vertex end = BRepBuilderAPI_MakeVertex(occ_q->Value(1.0));
        const TopoDS_Edge e1 = BRepBuilderAPI_MakeEdge(occ_p, start, middle, 0.0, u_star).Edge();
        const TopoDS_Edge e2 = BRepBuilderAPI_MakeEdge(occ_q, middle, end, v_star, 1.0).Edge();
        const gp_Pln plane(gp::XOY());

        auto run_occt = [&](TopoDS_Edge& m1, TopoDS_Edge& m2) {
            ChFi2d_FilletAPI api(e1, e2, plane);
            if (!api.Perform(radius) || api.NbResults(corner) < 1) {
                throw std::runtime_error("ChFi2d_FilletAPI found no fillet");
            }
            return api.Result(corner, m1, m2, -1);
        };
        TopoDS_Edge m1;
        TopoDS_Edge m2;
        const TopoDS_Edge arc = run_occt(m1, m2);
        // Curvature jump at each tangency point: trimmed edge vs arc.
        double arc_first = 0.0;
        double arc_last = 0.0;
        const Handle(Geom_Curve) arc_curve = BRep_Tool::Curve(arc, arc_first, arc_last);
        double occt_jump = 0.0;
        for (const TopoDS_Edge* edge : {&m1, &m2}) {
            double first = 0.0;
            double last = 0.0;
            const Handle(Geom_Curve) curve = BRep_Tool::Curve(*edge, first, last);
            // The end of the trimmed edge nearest to the arc, and the arc end there.
            const gp_Pnt a = curve->Value(first);
            const gp_Pnt b = curve->Value(last);
            const gp_Pnt s = arc_curve->Value(arc_first);
            const gp_Pnt e = arc_curve->Value(arc_last);
            const double da = std::min(a.Distance(s), a.Distance(e));
            const double db = std::min(b.Distance(s), b.Distance(e));
            const double u_edge = da < db ? first : last;
            const gp_Pnt at = curve->Value(u_edge);
            const double u_arc = at.Distance(s) < at.Distance(e) ? arc_first : arc_last;
            occt_jump = std::max(occt_jump, std::abs(curvature(curve, u_edge) - curvature(arc_curve, u_arc)));
        }
        report.info("d.curvature-jump-at-tangency",
                    format("ours (C3, setback 0.3): %.2e   OCCT circular fillet (G1, r = %.4f): %.2e",
                           our_jump, radius, occt_jump));
        scene.add(m1, gp_Vec(0.0, 6.0, 0.0));
        scene.add(arc, gp_Vec(0.0, 6.0, 0.0));
        scene.add(m2, gp_Vec(0.0, 6.0, 0.0));

        bezjoin::FilletOptions opts;
        opts.p_setback = 0.3;
        opts.q_setback = 0.3;
        opts.p_order = 3;
        opts.q_order = 3;
        const Pair pair = time_pair(
            options.quick ? 1 : 7, options.quick ? 1 : 1000,
            [&](int) {
                const bezjoin::Fillet f = bezjoin::fillet(p, q, opts);
                g_sink = g_sink + static_cast<double>(f.blend.degree());
            },
            options.quick ? 1 : 10,
            [&](int) {
                TopoDS_Edge a;
                TopoDS_Edge b;
                const TopoDS_Edge result = run_occt(a, b);
                g_sink = g_sink + static_cast<double>(result.IsNull());
            });
        timings.push_back({"fillet of two cubics (ours C3, OCCT G1 arc)", "bzj_fillet C3",
                           "ChFi2d_FilletAPI", pair});
    });
    expect_status(report, "d.fillet-error-no-crossing", BZJ_ERR_NO_INTERSECTION, [&] {
        const Curve low(2, 1, {0.0, 0.0, 1.0, 0.0});
        const Curve high(2, 1, {0.0, 1.0, 1.0, 1.0});
        bezjoin::FilletOptions opts;
        opts.p_setback = 0.1;
        opts.q_setback = 0.1;
        opts.p_order = 1;
        opts.q_order = 1;
        (void)bezjoin::fillet(low, high, opts);
    });
}

// r. Fillet by radius (bzj_fillet_radius) judged by OCCT. Corners: two lines
// (40 then 20 long) turning 45 (left), 90 (left; G2 and G3) and 135 degrees
// (right), and an arc of OCCT's circle of radius 10 (GC_MakeArcOfCircle
// through GeomConvert, into bzj_nurbs_new) followed by a line turning 70
// degrees left; radius 2 everywhere. Per corner three rows:
//   r.Gk-GeomLProp[...]    our three pieces as Geom_BezierCurve /
//                          Geom_BSplineCurve; GeomLProp_CLProps at both
//                          joins: unit tangents (1e-9), curvature (1e-7
//                          relative, 1e-9 absolute where the input piece is
//                          straight), normal and centre of curvature where
//                          the input piece is curved (1e-9 / 1e-7 relative to
//                          its radius of curvature); G3 also dkappa/ds on both
//                          sides by a finite difference of GeomLProp's
//                          curvature along OCCT's arc length (tolerance below).
//   r.cuts-vs-ChFi2d[...]  OCCT's own fillet of the same two edges
//                          (ChFi2d_FilletAPI, same radius, TopoDS_Edges in
//                          gp_Pln XOY): its arc's end points are our cuts
//                          (1e-9 relative to the corner's size).
//   r.curvature[...]       the blend's curvature rises to one peak and falls:
//                          report.curvature_extrema == 1, and OCCT's
//                          curvature at the report's 513 parameters
//                          (t = i/512) has one interior extremum and the same
//                          peak (1e-9 relative); peak beside 1/r, and the
//                          largest distance of our blend from OCCT's arc.
// Then one timing row: bzj_fillet_radius G2 beside ChFi2d_FilletAPI.

// Our curve as OCCT's (a Bezier curve as Geom_BezierCurve, a NURBS curve as
// Geom_BSplineCurve), 2D lifted to z = 0.
Handle(Geom_Curve) occ_curve(const Curve& c) {
    if (c.is_nurbs()) {
        return occ_bspline(c);
    }
    return occ_bezier(c);
}

// GeomLProp_CLProps at u: unit tangent, curvature and (only when asked: the
// normal is undefined on a straight piece) unit normal and centre.
struct LocalProps {
    gp_Vec tangent;
    double kappa = 0.0;
    gp_Vec normal;
    gp_Pnt centre;
};

LocalProps local_props(const Handle(Geom_Curve)& c, double u, bool with_normal) {
    GeomLProp_CLProps props(c, u, 2, 1e-12);
    if (!props.IsTangentDefined()) {
        throw std::runtime_error(format("GeomLProp_CLProps: no tangent at u = %g", u));
    }
    LocalProps out;
    gp_Dir t;
    props.Tangent(t);
    out.tangent = gp_Vec(t);
    out.kappa = props.Curvature();
    if (with_normal) {
        gp_Dir n;
        props.Normal(n);
        out.normal = gp_Vec(n);
        props.CentreOfCurvature(out.centre);
    }
    return out;
}

// d(kappa)/ds at the start (at_start) or the end of c, along the direction
// of travel: the quadratic through GeomLProp's curvature at the end and at
// parameter steps `fraction` and 2 `fraction` of the domain inward, placed at
// OCCT's arc lengths (GCPnts_AbscissaPoint::Length) from the end.
double dkappa_ds_at_end(const Handle(Geom_Curve)& c, bool at_start, double fraction) {
    const double a = c->FirstParameter();
    const double b = c->LastParameter();
    const double step = fraction * (b - a);
    const double u0 = at_start ? a : b;
    const double u1 = at_start ? a + step : b - step;
    const double u2 = at_start ? a + 2.0 * step : b - 2.0 * step;
    const GeomAdaptor_Curve adaptor(c);
    const double s1 = GCPnts_AbscissaPoint::Length(adaptor, std::min(u0, u1), std::max(u0, u1), 1e-13);
    const double s2 = GCPnts_AbscissaPoint::Length(adaptor, std::min(u0, u2), std::max(u0, u2), 1e-13);
    const double k0 = curvature(c, u0);
    const double k1 = curvature(c, u1);
    const double k2 = curvature(c, u2);
    // Derivative at s = 0 of the quadratic through (0, k0), (s1, k1), (s2, k2).
    const double inward = -k0 * (s1 + s2) / (s1 * s2) + k1 * s2 / (s1 * (s2 - s1)) - k2 * s1 / (s2 * (s2 - s1));
    return at_start ? inward : -inward;
}

struct RadiusCorner {
    std::string name;
    Curve p;
    Curve q;
    TopoDS_Edge e1;  // OCCT's edges of the same corner, sharing the vertex
    TopoDS_Edge e2;
    gp_Pnt vertex;
    double size = 1.0;  // max |coordinate| of the corner's end points, at least 1
    double turn = 0.0;  // two lines: |turning angle| (tangent length r tan(turn / 2)); else 0
    std::size_t order = 2;
};

void check_fillet_radius(Report& report, std::vector<Timing>& timings, const Options& options) {
    const double pi = 3.14159265358979323846;
    const double radius = 2.0;
    const gp_Pln plane(gp::XOY());
    std::vector<RadiusCorner> corners;

    // Two lines: P from A to the vertex V (40 long), Q from V to B (20 long),
    // turning `turn` radians (positive: to the left).
    auto lines = [&](const std::string& name, double turn, std::size_t order) {
        const gp_Pnt v(5.0, 3.0, 0.0);
        const double heading = 0.3;
        const gp_Dir d_in(std::cos(heading), std::sin(heading), 0.0);
        const gp_Dir d_out(std::cos(heading + turn), std::sin(heading + turn), 0.0);
        const gp_Pnt a = v.Translated(gp_Vec(d_in) * -40.0);
        const gp_Pnt b = v.Translated(gp_Vec(d_out) * 20.0);
        RadiusCorner c;
        c.name = name;
        c.p = Curve(2, 1, {a.X(), a.Y(), v.X(), v.Y()});
        c.q = Curve(2, 1, {v.X(), v.Y(), b.X(), b.Y()});
        const TopoDS_Vertex va = BRepBuilderAPI_MakeVertex(a);
        const TopoDS_Vertex vv = BRepBuilderAPI_MakeVertex(v);
        const TopoDS_Vertex vb = BRepBuilderAPI_MakeVertex(b);
        c.e1 = BRepBuilderAPI_MakeEdge(va, vv).Edge();
        c.e2 = BRepBuilderAPI_MakeEdge(vv, vb).Edge();
        c.vertex = v;
        c.size = std::max({1.0, std::abs(a.X()), std::abs(a.Y()), std::abs(v.X()), std::abs(v.Y()),
                           std::abs(b.X()), std::abs(b.Y())});
        c.turn = std::abs(turn);
        c.order = order;
        corners.push_back(std::move(c));
    };
    guarded(report, "r.corners", [&] {
        lines("lines 45/G2", pi / 4.0, 2);
        lines("lines 90/G2", pi / 2.0, 2);
        lines("lines 90/G3", pi / 2.0, 3);
        lines("lines 135 right/G2", -3.0 * pi / 4.0, 2);
        // The arc: circle of radius 10 about the origin from -0.6 to 1.0 rad
        // (counter-clockwise, 16 long), then a line 20 long turning 70
        // degrees left of the arc's end tangent; the fillet lies inside the
        // circle.
        const double a0 = -0.6;
        const double a1 = 1.0;
        const Handle(Geom_TrimmedCurve) arc_occ =
            GC_MakeArcOfCircle(gp_Circ(gp::XOY(), 10.0), a0, a1, true).Value();
        const Handle(Geom_BSplineCurve) arc_bspline = GeomConvert::CurveToBSplineCurve(arc_occ);
        const gp_Pnt v = arc_occ->EndPoint();
        const gp_Dir end_tangent(-std::sin(a1), std::cos(a1), 0.0);
        const gp_Dir line_dir = end_tangent.Rotated(gp::OZ(), 70.0 * pi / 180.0);
        const gp_Pnt b = v.Translated(gp_Vec(line_dir) * 20.0);
        RadiusCorner c;
        c.name = "arc+line/G2";
        c.p = ours_from_occ(arc_bspline, 2);
        c.q = Curve(2, 1, {v.X(), v.Y(), b.X(), b.Y()});
        const TopoDS_Vertex va = BRepBuilderAPI_MakeVertex(arc_occ->StartPoint());
        const TopoDS_Vertex vv = BRepBuilderAPI_MakeVertex(v);
        const TopoDS_Vertex vb = BRepBuilderAPI_MakeVertex(b);
        c.e1 = BRepBuilderAPI_MakeEdge(arc_occ->BasisCurve(), va, vv, a0, a1).Edge();
        c.e2 = BRepBuilderAPI_MakeEdge(vv, vb).Edge();
        c.vertex = v;
        c.size = std::max({1.0, 10.0, std::abs(b.X()), std::abs(b.Y())});
        c.order = 2;
        corners.push_back(std::move(c));
        report.info("r.corners",
                    format("radius %g; lines 40 + 20 long turning 45 / 90 (left) and 135 (right) degrees; "
                           "arc: GeomConvert of GC_MakeArcOfCircle (r 10, degree %d, rational %s, %d poles) + "
                           "line turning 70 degrees left",
                           radius, arc_bspline->Degree(), arc_bspline->IsRational() ? "yes" : "no",
                           arc_bspline->NbPoles()));
    });

    // OCCT's fillet of a corner: the arc's edge, its circle, its end points.
    struct OcctFillet {
        TopoDS_Edge arc;
        Handle(Geom_Circle) circle;
        gp_Pnt a;
        gp_Pnt b;
    };
    auto occt_fillet = [&](const RadiusCorner& c) {
        ChFi2d_FilletAPI api(c.e1, c.e2, plane);
        if (!api.Perform(radius) || api.NbResults(c.vertex) < 1) {
            throw std::runtime_error("ChFi2d_FilletAPI found no fillet");
        }
        TopoDS_Edge m1;
        TopoDS_Edge m2;
        OcctFillet f;
        f.arc = api.Result(c.vertex, m1, m2, -1);
        double first = 0.0;
        double last = 0.0;
        const Handle(Geom_Curve) curve = BRep_Tool::Curve(f.arc, first, last);
        const Handle(Geom_TrimmedCurve) trimmed = Handle(Geom_TrimmedCurve)::DownCast(curve);
        f.circle = Handle(Geom_Circle)::DownCast(trimmed.IsNull() ? curve : trimmed->BasisCurve());
        if (f.circle.IsNull()) {
            throw std::runtime_error("ChFi2d_FilletAPI's fillet is not a circle");
        }
        f.a = curve->Value(first);
        f.b = curve->Value(last);
        return f;
    };

    for (const RadiusCorner& c : corners) {
        std::unique_ptr<bezjoin::RadiusFillet> ours;
        const std::string gk_name = format("r.Gk-GeomLProp[%s]", c.name.c_str());
        guarded(report, gk_name, [&] {
            ours = std::make_unique<bezjoin::RadiusFillet>(bezjoin::fillet_radius(c.p, c.q, radius, c.order));
            const Handle(Geom_Curve) pieces[3] = {occ_curve(ours->p_trimmed), occ_curve(ours->blend),
                                                  occ_curve(ours->q_trimmed)};
            double tangent_gap = 0.0;
            double kappa_rel = 0.0;  // where the input piece is curved
            double kappa_abs = 0.0;  // where it is straight
            double normal_gap = 0.0;
            double centre_gap = 0.0;
            std::string kappas;
            // Join 0: P_trim's end | blend's start; join 1: blend's end | Q_trim's start.
            for (int join = 0; join < 2; ++join) {
                const Handle(Geom_Curve)& input = join == 0 ? pieces[0] : pieces[2];
                const double u_input = join == 0 ? input->LastParameter() : input->FirstParameter();
                const double u_blend = join == 0 ? pieces[1]->FirstParameter() : pieces[1]->LastParameter();
                const bool curved = curvature(input, u_input) > 1e-12;
                const LocalProps x = local_props(input, u_input, curved);
                const LocalProps y = local_props(pieces[1], u_blend, curved);
                tangent_gap = std::max(tangent_gap, (x.tangent - y.tangent).Magnitude());
                if (curved) {
                    kappa_rel = std::max(kappa_rel, std::abs(x.kappa - y.kappa) / x.kappa);
                    normal_gap = std::max(normal_gap, (x.normal - y.normal).Magnitude());
                    centre_gap = std::max(centre_gap, x.centre.Distance(y.centre) * x.kappa);
                } else {
                    kappa_abs = std::max(kappa_abs, std::abs(x.kappa - y.kappa));
                }
                kappas += format("%s%s k %.6g | %.6g", join == 0 ? "" : ", ", join == 0 ? "P|R" : "R|Q", x.kappa,
                                 y.kappa);
            }
            // dkappa/ds on both sides of each join (finite differences on
            // 1e-5 of each piece's domain: the quadratic's error falls as the
            // step squared, 4e-3 at 1e-3 and 4e-7 at 1e-5 on the G3 corner),
            // scale-free: times L / kappa_peak, L the blend's length. A G2
            // blend's jump there is about 4, a G3 blend's must be 0.
            const double length = GCPnts_AbscissaPoint::Length(GeomAdaptor_Curve(pieces[1]), 1e-13);
            const double peak = std::max(std::abs(ours->report.curvature_min), std::abs(ours->report.curvature_max));
            const double dk_scale = peak / length;
            const double fraction = 1e-5;
            const double dk_p = dkappa_ds_at_end(pieces[0], false, fraction);
            const double dk_r0 = dkappa_ds_at_end(pieces[1], true, fraction);
            const double dk_r1 = dkappa_ds_at_end(pieces[1], false, fraction);
            const double dk_q = dkappa_ds_at_end(pieces[2], true, fraction);
            const double dk_jump = std::max(std::abs(dk_p - dk_r0), std::abs(dk_r1 - dk_q)) / dk_scale;
            const double dk_tolerance = 1e-4;
            bool pass = tangent_gap <= 1e-9 && kappa_rel <= 1e-7 && kappa_abs <= 1e-9 && normal_gap <= 1e-9 &&
                        centre_gap <= 1e-7;
            if (c.order >= 3) {
                pass = pass && dk_jump <= dk_tolerance;
            }
            report.row(pass, gk_name, tangent_gap, 1e-9,
                       format("G%zu, blend degree %zu; unit tangents above; curvature %s: |dk| rel %.1e (tol 1e-7), "
                              "abs %.1e (tol 1e-9); normal %.1e (tol 1e-9), centre %.1e (tol 1e-7 rel); "
                              "dkappa/ds jump (FD, x L/kappa_peak) %.1e%s",
                              c.order, ours->blend.degree(), kappas.c_str(), kappa_rel, kappa_abs, normal_gap,
                              centre_gap, dk_jump,
                              c.order >= 3 ? format(" (tol %.0e)", dk_tolerance).c_str() : " (G2: not required)"));
        });
        if (!ours) {
            continue;
        }
        const std::string cut_name = format("r.cuts-vs-ChFi2d[%s]", c.name.c_str());
        std::unique_ptr<OcctFillet> theirs;
        guarded(report, cut_name, [&] {
            theirs = std::make_unique<OcctFillet>(occt_fillet(c));
            const std::vector<double> p_end = ours->p_trimmed.eval(ours->p_trimmed.domain().second);
            const std::vector<double> q_start = ours->q_trimmed.eval(ours->q_trimmed.domain().first);
            const gp_Pnt pe(p_end[0], p_end[1], 0.0);
            const gp_Pnt qs(q_start[0], q_start[1], 0.0);
            // OCCT's arc may run either way: the pairing of the nearer ends.
            const double straight = std::max(pe.Distance(theirs->a), qs.Distance(theirs->b));
            const double swapped = std::max(pe.Distance(theirs->b), qs.Distance(theirs->a));
            const double gap = std::min(straight, swapped) / c.size;
            const double radius_gap = std::abs(theirs->circle->Radius() - radius) / radius;
            const double worst = std::max(gap, radius_gap);
            const gp_Pnt centre = theirs->circle->Location();
            report.row(worst <= 1e-9, cut_name, worst, 1e-9,
                       format("OCCT arc r %.12g, centre (%.9f, %.9f); cuts P(%.9f, %.9f) Q(%.9f, %.9f), "
                              "%.9f / %.9f from the vertex%s; gap relative to size %g",
                              theirs->circle->Radius(), centre.X(), centre.Y(), pe.X(), pe.Y(), qs.X(), qs.Y(),
                              pe.Distance(c.vertex), qs.Distance(c.vertex),
                              c.turn > 0.0 ? format(" (r tan(theta/2) = %.9f)", radius * std::tan(0.5 * c.turn)).c_str()
                                           : " (chords)",
                              c.size));
        });
        const std::string shape_name = format("r.curvature[%s]", c.name.c_str());
        guarded(report, shape_name, [&] {
            const BzjFairnessReport& r = ours->report;
            const Handle(Geom_Curve) blend = occ_curve(ours->blend);
            // OCCT's curvature (unsigned) at the report's parameters i / 512.
            std::vector<double> kappas;
            for (int i = 0; i <= 512; ++i) {
                kappas.push_back(curvature(blend, i / 512.0));
            }
            const double occt_max = *std::max_element(kappas.begin(), kappas.end());
            const double occt_min = *std::min_element(kappas.begin(), kappas.end());
            const double noise = 1e-9 * std::max(occt_max - occt_min, occt_max);
            int occt_extrema = 0;
            int direction = 0;
            for (std::size_t i = 1; i < kappas.size(); ++i) {
                const double step = kappas[i] - kappas[i - 1];
                const int now = step > noise ? 1 : step < -noise ? -1 : 0;
                if (now != 0) {
                    occt_extrema += direction != 0 && now != direction ? 1 : 0;
                    direction = now;
                }
            }
            // The report's peak (signed in 2D: a right turn has negative
            // curvature, its peak is curvature_min).
            const double peak = std::max(std::abs(r.curvature_min), std::abs(r.curvature_max));
            const double peak_gap = std::abs(peak - occt_max) / occt_max;
            // Our blend against OCCT's arc: | |X - centre| - r |, 2049 samples.
            double deviation = 0.0;
            double centre_x = 0.0;
            double centre_y = 0.0;
            double arc_r = radius;
            if (theirs) {
                centre_x = theirs->circle->Location().X();
                centre_y = theirs->circle->Location().Y();
                arc_r = theirs->circle->Radius();
                std::vector<double> ts;
                for (int i = 0; i <= 2048; ++i) {
                    ts.push_back(i / 2048.0);
                }
                const std::vector<double> xs = ours->blend.eval_many(ts);
                for (std::size_t i = 0; i < ts.size(); ++i) {
                    deviation = std::max(deviation,
                                         std::abs(std::hypot(xs[2 * i] - centre_x, xs[2 * i + 1] - centre_y) - arc_r));
                }
            }
            const bool pass = r.curvature_extrema == 1 && occt_extrema == 1 && peak_gap <= 1e-9 && theirs;
            report.row(pass, shape_name, peak_gap, 1e-9,
                       format("extrema: report %zu, OCCT %d (need 1); peak |kappa| report %.6f vs OCCT %.6f, "
                              "1/r = %.6f (x%.3f); report range [%.6g, %.6g], energy %.4g; largest distance "
                              "blend - OCCT arc %.4e (%.2e r)%s",
                              r.curvature_extrema, occt_extrema, peak, occt_max, 1.0 / radius, peak * radius,
                              r.curvature_min, r.curvature_max, r.energy, deviation, deviation / radius,
                              theirs ? "" : " [no OCCT arc]"));
        });
    }

    // bzj_connect_geometric with NULL shapes is the blend's own solve: on the
    // 90-degree corner, P and Q at the arc's touching points (u_t = 1 - r /
    // 40, v_t = r / 20) give the fillet's blend; the shape values it returns,
    // passed back explicitly, give the same curve and come back unchanged.
    // (Informational: from the trimmed pieces, parametrised afresh, the fair
    // search stops at another point of its flat minimum.)
    guarded(report, "r.connect_geometric[lines 90/G2]", [&] {
        const RadiusCorner* c = nullptr;
        for (const RadiusCorner& x : corners) {
            if (x.name == "lines 90/G2") {
                c = &x;
            }
        }
        if (c == nullptr) {
            throw std::runtime_error("no 90-degree corner");
        }
        auto difference = [](const Curve& a, const Curve& b) {
            const std::vector<double> x = a.points();
            const std::vector<double> y = b.points();
            double worst = x.size() == y.size() ? 0.0 : INFINITY;
            for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
                worst = std::max(worst, std::abs(x[i] - y[i]));
            }
            return worst;
        };
        const double tangent_length = radius * std::tan(0.5 * c->turn);
        const std::vector<double> pp = c->p.points();
        const std::vector<double> qp = c->q.points();
        const double u_t = 1.0 - tangent_length / std::hypot(pp[2] - pp[0], pp[3] - pp[1]);
        const double v_t = tangent_length / std::hypot(qp[2] - qp[0], qp[3] - qp[1]);
        const bezjoin::RadiusFillet f = bezjoin::fillet_radius(c->p, c->q, radius, 2);
        bezjoin::GeometricOptions fair;
        fair.p_order = 2;
        fair.q_order = 2;
        const bezjoin::GeometricConnection g = bezjoin::connect_geometric(c->p, u_t, c->q, v_t, fair);
        bezjoin::GeometricOptions given = fair;
        given.p_shape = g.p_shape;
        given.q_shape = g.q_shape;
        const bezjoin::GeometricConnection h = bezjoin::connect_geometric(c->p, u_t, c->q, v_t, given);
        double shapes_back = 0.0;
        for (std::size_t i = 0; i < 2; ++i) {
            shapes_back = std::max({shapes_back, std::abs(h.p_shape[i] - g.p_shape[i]),
                                    std::abs(h.q_shape[i] - g.q_shape[i])});
        }
        const bezjoin::GeometricConnection t =
            bezjoin::connect_geometric(f.p_trimmed, 1.0, f.q_trimmed, 0.0, fair);
        const double worst = std::max({difference(g.curve, f.blend), difference(h.curve, g.curve), shapes_back}) /
                             c->size;
        report.row(worst <= 1e-9, "r.connect_geometric[lines 90/G2]", worst, 1e-9,
                   format("fair shapes P (%.6g, %.6g) Q (%.6g, %.6g), energy %.10g (fillet's %.10g); explicit "
                          "shapes: same curve, shapes back %.1e; from the trimmed pieces: blend %.1e away, "
                          "energy %.10g",
                          g.p_shape[0], g.p_shape[1], g.q_shape[0], g.q_shape[1], g.report.energy,
                          f.report.energy, shapes_back, difference(t.curve, f.blend), t.report.energy));
    });

    // Timing: bzj_fillet_radius (G2) beside ChFi2d_FilletAPI, same radius,
    // on the 90-degree corner of two lines and on the arc+line corner (OCCT
    // on edges built once; Perform + Result per call).
    for (const char* which : {"lines 90/G2", "arc+line/G2"}) {
        const RadiusCorner* c = nullptr;
        for (const RadiusCorner& x : corners) {
            if (x.name == which) {
                c = &x;
            }
        }
        if (c == nullptr) {
            continue;
        }
        guarded(report, format("timing.fillet_radius[%s]", which), [&] {
            const Pair pair = time_pair(
                options.quick ? 1 : 7, options.quick ? 1 : 20,
                [&](int) {
                    const bezjoin::RadiusFillet f = bezjoin::fillet_radius(c->p, c->q, radius, 2);
                    g_sink = g_sink + f.report.curvature_max;
                },
                options.quick ? 1 : 200,
                [&](int) {
                    const OcctFillet f = occt_fillet(*c);
                    g_sink = g_sink + f.circle->Radius();
                });
            timings.push_back({format("fillet r = 2, %s (ours G2, OCCT G1 arc)", which), "bzj_fillet_radius G2",
                               "ChFi2d_FilletAPI", pair});
        });
    }
}

// e. merge: Segment of R at mu gives back P^ and Q^; our deviation vs OCCT's
// best one-span fit of the same two curves.
void check_merge(Report& report, StepScene& scene, std::vector<Timing>& timings,
                 const Options& options) {
    const Curve p(3, 3, {0.0, 0.0, 0.0, 0.4, 0.5, 0.1, 0.9, 0.7, 0.2, 1.4, 0.75, 0.2});
    const Curve q(3, 3, {1.4, 0.75, 0.2, 1.9, 0.8, 0.2, 2.4, 0.5, 0.1, 2.8, 0.0, 0.0});
    const Handle(Geom_BezierCurve) occ_p = occ_bezier(p);
    const Handle(Geom_BezierCurve) occ_q = occ_bezier(q);
    bezjoin::MergeOptions opts;
    opts.metric = BZJ_METRIC_L2;
    opts.split = BZJ_SPLIT_OPTIMAL;
    opts.fix_ends = true;
    const double tolerance = 1e-12;
    guarded(report, "e.merge-Segment-at-mu", [&] {
        const bezjoin::Merge m = bezjoin::merge(p, q, opts);
        const double mu = m.report.mu;
        const Handle(Geom_BezierCurve) r = occ_bezier(m.merged);
        const double gap = std::max(pole_difference(m.p_hat, occ_segment(r, 0.0, mu)),
                                    pole_difference(m.q_hat, occ_segment(r, mu, 1.0)));
        report.row(gap <= tolerance, "e.merge-Segment-at-mu", gap, tolerance,
                   format("L2 metric, optimal mu = %.6f, ends fixed", mu));

        // Our reported deviation vs OCCT's evaluation of |R(mu u) - P(u)|, |R(mu + (1-mu) v) - Q(v)|.
        double measured = 0.0;
        for (int i = 0; i <= 2000; ++i) {
            const double s = i / 2000.0;
            measured = std::max(measured, r->Value(mu * s).Distance(occ_p->Value(s)));
            measured = std::max(measured, r->Value(mu + (1.0 - mu) * s).Distance(occ_q->Value(s)));
        }
        const double reported = m.report.max_deviation;
        const double disagreement = std::abs(reported - measured) / std::max(measured, 1e-300);
        report.row(disagreement <= 1e-3, "e.merge-reported-deviation", disagreement, 1e-3,
                   format("reported %.6e, OCCT-evaluated %.6e (2001 samples per curve)", reported,
                          measured));

        // OCCT's least-squares fit of the same samples: one span, same degree.
        const int degree = static_cast<int>(m.merged.degree());
        const int samples = 101;
        TColgp_Array1OfPnt points(1, 2 * samples - 1);
        for (int i = 0; i < samples; ++i) {
            points(i + 1) = occ_p->Value(i / double(samples - 1));
        }
        for (int i = 1; i < samples; ++i) {
            points(samples + i) = occ_q->Value(i / double(samples - 1));
        }
        GeomAPI_PointsToBSpline fit(points, degree, degree, GeomAbs_C2, 1.0);
        if (!fit.IsDone()) {
            throw std::runtime_error("GeomAPI_PointsToBSpline failed");
        }
        const Handle(Geom_BSplineCurve) occ_fit = fit.Curve();
        const bool one_span = occ_fit->NbKnots() == 2 && occ_fit->Degree() == degree;
        report.row(one_span, "e.OCCT-fit-one-span-same-degree",
                   std::abs(occ_fit->NbKnots() - 2) + std::abs(occ_fit->Degree() - degree), 0.0,
                   format("GeomAPI_PointsToBSpline of %d samples: %d knots, degree %d (ours %d)",
                          points.Upper(), occ_fit->NbKnots(), occ_fit->Degree(), degree));
        // Same geometric measure for both: the largest distance from a sample
        // of P-then-Q to the (bounded) curve: the nearest orthogonal
        // projection or the nearer curve end, whichever is closer.
        auto distance_to = [&](const Handle(Geom_Curve)& curve) {
            const gp_Pnt first = curve->Value(curve->FirstParameter());
            const gp_Pnt last = curve->Value(curve->LastParameter());
            double worst = 0.0;
            for (int i = 1; i <= points.Upper(); ++i) {
                double d = std::min(points(i).Distance(first), points(i).Distance(last));
                GeomAPI_ProjectPointOnCurve projection(points(i), curve);
                if (projection.NbPoints() > 0) {
                    d = std::min(d, projection.LowerDistance());
                }
                worst = std::max(worst, d);
            }
            return worst;
        };
        const double ours_geometric = distance_to(r);
        const double occt_geometric = distance_to(occ_fit);
        // Criterion: ours within 2x of OCCT's least-squares fit. Ours minimises
        // the change of control points (L2 metric) under C^n at mu, not the
        // distance, so "ours <= OCCT" does not hold by construction; measured
        // ratio 0.45 here and 0.12-1.67 on 40 random cubic pairs. The samples
        // are among the 2001 per curve above, so the distance to our curve
        // cannot exceed the parametric deviation measured there.
        const double factor = 2.0;
        const double ratio = ours_geometric / occt_geometric;
        const bool comparable = std::isfinite(ours_geometric) && std::isfinite(reported) &&
                                std::isfinite(occt_geometric) && occt_geometric > 0.0 &&
                                ours_geometric <= measured * (1.0 + 1e-9) && ratio <= factor;
        report.row(one_span && comparable, "e.merge-vs-OCCT-fit ours<=2x LSQ", ratio, factor,
                   format("max distance of P-then-Q to the curve: ours %.3e (parametric %.3e), "
                          "OCCT one-span fit %.3e",
                          ours_geometric, reported, occt_geometric));
        scene.add(m.merged, gp_Vec(0.0, 9.0, 0.0));
        scene.add(Handle(Geom_Curve)(occ_fit), gp_Vec(0.0, 10.0, 0.0));
        scene.add(p, gp_Vec(0.0, 11.0, 0.0));
        scene.add(q, gp_Vec(0.0, 11.0, 0.0));

        const Pair pair = time_pair(
            options.quick ? 1 : 9, options.quick ? 1 : 1000,
            [&](int) {
                const bezjoin::Merge again = bezjoin::merge(p, q, opts);
                g_sink = g_sink + again.report.mu;
            },
            options.quick ? 1 : 100,
            [&](int) {
                GeomAPI_PointsToBSpline again(points, degree, degree, GeomAbs_C2, 1.0);
                g_sink = g_sink + static_cast<double>(again.Curve()->NbPoles());
            });
        timings.push_back({"merge two cubics into one", "bzj_merge L2 optimal mu",
                           "GeomAPI_PointsToBSpline 201 points", pair});
        // The paper's setting: discrete metric, mu = 1/2 (one KKT solve, no search).
        bezjoin::MergeOptions paper;
        paper.metric = BZJ_METRIC_DISCRETE;
        paper.split = BZJ_SPLIT_HALF;
        paper.fix_ends = true;
        const Pair paper_pair = time_pair(
            options.quick ? 1 : 9, options.quick ? 1 : 5000,
            [&](int) {
                const bezjoin::Merge again = bezjoin::merge(p, q, paper);
                g_sink = g_sink + again.report.mu;
            },
            options.quick ? 1 : 100,
            [&](int) {
                GeomAPI_PointsToBSpline again(points, degree, degree, GeomAbs_C2, 1.0);
                g_sink = g_sink + static_cast<double>(again.Curve()->NbPoles());
            });
        timings.push_back({"merge two cubics into one (paper)", "bzj_merge discrete mu=1/2",
                           "GeomAPI_PointsToBSpline 201 points", paper_pair});
    });
    expect_status(report, "e.merge-error-mu-outside", BZJ_ERR_INVALID_ARGUMENT, [&] {
        bezjoin::MergeOptions bad;
        bad.split = BZJ_SPLIT_GIVEN;
        bad.mu = 1.5;
        (void)bezjoin::merge(p, q, bad);
    });
    expect_status(report, "e.merge-error-keep-both", BZJ_ERR_INCONSISTENT, [&] {
        bezjoin::MergeOptions bad;
        bad.keep_p = true;
        bad.keep_q = true;
        (void)bezjoin::merge(p, q, bad);  // P and Q are not one curve: nothing may change
    });
}

// f. Lagrange spline: the given points lie on OCCT's curve; C1 by OCCT.
void check_lagrange(Report& report, StepScene& scene) {
    guarded(report, "f.lagrange-points-on-curve", [&] {
        const std::size_t dim = 3;
        const std::vector<double> params = {0.0, 0.7, 1.5, 2.1, 3.0, 3.6};
        auto helix = [](double x) { return gp_Pnt(std::cos(x), std::sin(x), 0.3 * x); };
        std::vector<double> nodes;
        for (double x : params) {
            const gp_Pnt pt = helix(x);
            nodes.insert(nodes.end(), {pt.X(), pt.Y(), pt.Z()});
        }
        std::vector<gp_Pnt> given;  // every given point with its global parameter
        std::vector<double> given_at;
        for (std::size_t i = 0; i < params.size(); ++i) {
            given.push_back(helix(params[i]));
            given_at.push_back(params[i]);
        }
        const double h0 = params[1] - params[0];
        std::vector<double> first_inner;
        for (double f : {1.0 / 3.0, 2.0 / 3.0}) {
            const double x = params[0] + f * h0;
            const gp_Pnt pt = helix(x);
            first_inner.insert(first_inner.end(), {pt.X(), pt.Y(), pt.Z()});
            given.push_back(pt);
            given_at.push_back(x);
        }
        std::vector<double> second_inner;
        for (std::size_t i = 1; i + 1 < params.size(); ++i) {
            const double x = params[i] + (params[i + 1] - params[i]) * 2.0 / 3.0;
            const gp_Pnt pt = helix(x);
            second_inner.insert(second_inner.end(), {pt.X(), pt.Y(), pt.Z()});
            given.push_back(pt);
            given_at.push_back(x);
        }
        const std::vector<Curve> segments =
            bezjoin::lagrange_spline(dim, nodes, params, first_inner, second_inner);
        std::vector<const Curve*> pieces;
        std::vector<double> intervals;
        for (std::size_t i = 0; i < segments.size(); ++i) {
            pieces.push_back(&segments[i]);
            intervals.push_back(params[i + 1] - params[i]);
        }
        const Chain chain = make_chain(pieces, intervals, params[0]);
        double miss = chain.pole_gap;
        for (std::size_t i = 0; i < given.size(); ++i) {
            miss = std::max(miss, chain.curve->Value(given_at[i]).Distance(given[i]) / chain.size);
        }
        const double tolerance = 1e-12;
        report.row(miss <= tolerance, "f.lagrange-points-on-curve", miss, tolerance,
                   format("%zu given points at their parameters on OCCT's cubic B-spline", given.size()));
        double jump = 0.0;
        bool all_removable = true;
        bool any_c2 = false;
        for (int index = 2; index < static_cast<int>(chain.knots.size()); ++index) {
            const JoinVerdict verdict = judge_join(chain, index, 1, 1e-9 * chain.size);
            all_removable = all_removable && verdict.removable;
            any_c2 = any_c2 || verdict.stricter;
            jump = std::max(jump, verdict.jump);
        }
        report.row(all_removable && jump <= 1e-9, "f.lagrange-C1-by-OCCT", jump, 1e-9,
                   format("%zu interior knots: RemoveKnot to mult 2 %s; C2 somewhere: %s",
                          chain.knots.size() - 2, all_removable ? "ok" : "REFUSED",
                          any_c2 ? "yes" : "no"));
        scene.add(Handle(Geom_Curve)(chain.curve), gp_Vec(0.0, 14.0, 0.0));
    });
    expect_status(report, "f.lagrange-error-params-order", BZJ_ERR_INVALID_ARGUMENT, [&] {
        const std::vector<double> nodes = {0.0, 0.0, 1.0, 0.0, 2.0, 1.0};
        (void)bezjoin::lagrange_spline(2, nodes, {0.0, 1.0, 0.5}, {0.3, 0.1, 0.6, 0.1}, {1.6, 0.6});
    });
}

// g. The other wrappers of bezjoin.hpp (every C function has one; a-f cover
// the first ones): each is called and its result checked by its defining
// property, with OCCT as the judge where it has an opinion.

// The chord-linear cubic from a to b bulged by h (normal, 2D): its
// coordinate along b - a is exactly t, so t = <X - a, b - a> / |b - a|^2 for
// any point X on it.
std::vector<double> bulged_side(const double* a, const double* b, double h) {
    const double nx = -(b[1] - a[1]);
    const double ny = b[0] - a[0];
    std::vector<double> points;
    for (int i = 0; i <= 3; ++i) {
        const double f = i / 3.0;
        const double bulge = (i == 1 || i == 2) ? h : 0.0;
        points.push_back(a[0] + f * (b[0] - a[0]) + bulge * nx);
        points.push_back(a[1] + f * (b[1] - a[1]) + bulge * ny);
    }
    return points;
}

double chord_parameter(const double* a, const double* b, const std::vector<double>& x) {
    const double dx = b[0] - a[0];
    const double dy = b[1] - a[1];
    return ((x[0] - a[0]) * dx + (x[1] - a[1]) * dy) / (dx * dx + dy * dy);
}

// C^k of pieces on knot intervals `widths` by OCCT (RemoveKnot and the
// one-sided derivatives at every interior knot); the worst jump, or INFINITY
// when RemoveKnot refuses a join.
double chain_defect(const std::vector<const Curve*>& pieces, const std::vector<double>& widths, int k,
                    double tolerance) {
    const Chain chain = make_chain(pieces, widths);
    double worst = chain.pole_gap;
    for (int index = 2; index < static_cast<int>(chain.knots.size()); ++index) {
        const JoinVerdict verdict = judge_join(chain, index, k, tolerance * chain.size);
        worst = std::max(worst, verdict.removable ? verdict.jump : INFINITY);
    }
    return worst;
}

void check_auto_scale(Report& report) {
    const double tolerance = 1e-8;  // the residual bezjoin.h promises for connect
    guarded(report, "g.connect_auto_scale", [&] {
        // A cubic P and a quartic Q round a gap: the fairest scale is interior
        // to the library's search range.
        const Curve p(3, 3, {0.0, 0.0, 0.0, 1.0, 0.3, 0.1, 2.0, 0.1, 0.2, 3.0, 0.0, 0.0});
        const Curve q(3, 4, {4.0, 1.0, 0.0, 4.2, 2.0, 0.1, 4.1, 3.0, -0.1, 4.0, 4.0, 0.0, 3.8, 5.0, 0.0});
        bezjoin::ConnectOptions opts;
        opts.p_order = 2;
        opts.q_order = 3;
        opts.p_scale = -1.0;  // ignored
        const double u0 = 0.8;
        const double v0 = 0.2;
        const bezjoin::AutoScaledConnection r = bezjoin::connect_auto_scale(p, u0, q, v0, opts);
        const double s = r.scale;
        // R^(k)(0) = s^k P^(k)(u0), k <= 2, and R^(k)(1) = s^k Q^(k)(v0), k <= 3,
        // with P's and Q's derivatives by OCCT (relative to max(1, |value|)).
        const Handle(Geom_BezierCurve) occ_p = occ_bezier(p);
        const Handle(Geom_BezierCurve) occ_q = occ_bezier(q);
        double worst = 0.0;
        for (int k = 0; k <= 3; ++k) {
            for (int end = 0; end < 2; ++end) {
                if (end == 0 && k > 2) {
                    continue;
                }
                const gp_Vec theirs = (k == 0 ? gp_Vec((end == 0 ? occ_p->Value(u0) : occ_q->Value(v0)).XYZ())
                                              : (end == 0 ? occ_p->DN(u0, k) : occ_q->DN(v0, k))) *
                                      std::pow(s, k);
                const std::vector<double> ours = r.curve.eval(end == 0 ? 0.0 : 1.0, 3);
                const gp_Vec mine(ours[3 * k], ours[3 * k + 1], ours[3 * k + 2]);
                worst = std::max(worst, (mine - theirs).Magnitude() / std::max(1.0, theirs.Magnitude()));
            }
        }
        // s minimises the fairness energy integral |R''|^2: connect() with a
        // scale 1.01 times larger or smaller gives no fairer blend (OCCT's DN,
        // Simpson's rule on 400 intervals).
        auto energy = [&](const Curve& c) {
            const Handle(Geom_BezierCurve) occ = occ_bezier(c);
            double sum = 0.0;
            for (int i = 0; i <= 400; ++i) {
                const double w = (i == 0 || i == 400) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
                sum += w * occ->DN(i / 400.0, 2).SquareMagnitude();
            }
            return sum / (3.0 * 400.0);
        };
        const double e = energy(r.curve);
        double e_other = INFINITY;
        for (double factor : {1.01, 1.0 / 1.01}) {
            bezjoin::ConnectOptions fixed = opts;
            fixed.p_scale = s * factor;
            fixed.q_scale = s * factor;
            e_other = std::min(e_other, energy(bezjoin::connect(p, u0, q, v0, fixed)));
        }
        const bool pass = s > 0.0 && std::isfinite(s) && r.curve.degree() == 6 && e <= e_other &&
                          worst <= tolerance;
        report.row(pass, "g.connect_auto_scale", worst, tolerance,
                   format("s = %.6f: ends match s^k P^(k)(u0), s^k Q^(k)(v0) by OCCT; energy %.4e <= %.4e "
                          "at s * 1.01^+-1",
                          s, e, e_other));
    });
    guarded(report, "g.connect_points", [&] {
        // The handle-free entries give connect()'s and connect_auto_scale()'s
        // control points bit for bit (the same curves, the same solve).
        const Curve p(3, 3, {0.0, 0.0, 0.0, 1.0, 0.3, 0.1, 2.0, 0.1, 0.2, 3.0, 0.0, 0.0});
        const Curve q(3, 4, {4.0, 1.0, 0.0, 4.2, 2.0, 0.1, 4.1, 3.0, -0.1, 4.0, 4.0, 0.0, 3.8, 5.0, 0.0});
        bezjoin::ConnectOptions opts;
        opts.p_order = 2;
        opts.q_order = 3;
        opts.p_scale = 0.7;
        opts.q_scale = 0.9;
        const std::vector<double> given =
            bezjoin::connect_points(3, p.points(), 0.8, q.points(), 0.2, 2, 3, 0.7, 0.9);
        const bool same_given = given == bezjoin::connect(p, 0.8, q, 0.2, opts).points();
        const auto automatic = bezjoin::connect_points_auto_scale(3, p.points(), 0.8, q.points(), 0.2, 2, 3);
        const bezjoin::AutoScaledConnection r = bezjoin::connect_auto_scale(p, 0.8, q, 0.2, opts);
        const bool same_auto = automatic.first == r.curve.points() && automatic.second == r.scale;
        report.row(same_given && same_auto, "g.connect_points", same_given && same_auto ? 0.0 : 1.0, 0.0,
                   "connect_points / connect_points_auto_scale equal connect / connect_auto_scale bit for bit");
    });
    guarded(report, "g.fillet_auto_scale", [&] {
        // Lines of speed 8 as cubics crossing at the origin, C^3, setback 0.5:
        // the chosen scale keeps the blend's control polygon in the corner.
        const Curve p(2, 3, {-4.0, 0.0, -4.0 / 3.0, 0.0, 4.0 / 3.0, 0.0, 4.0, 0.0});
        const Curve q(2, 3, {0.0, -4.0, 0.0, -4.0 / 3.0, 0.0, 4.0 / 3.0, 0.0, 4.0});
        bezjoin::FilletOptions opts;
        opts.p_setback = 0.5;
        opts.q_setback = 0.5;
        opts.p_order = 3;
        opts.q_order = 3;
        const bezjoin::AutoScaledFillet f = bezjoin::fillet_auto_scale(p, q, opts);
        const double s = f.scale;
        const double u0 = 0.5 - 0.5 / 8.0;
        const double v0 = 0.5 + 0.5 / 8.0;
        const double worst = chain_defect({&f.p_trimmed, &f.blend, &f.q_trimmed}, {u0, s, 1.0 - v0}, 3,
                                          tolerance);
        bool inside = true;
        const std::vector<double> blend = f.blend.points();
        for (std::size_t i = 0; i < blend.size(); i += 2) {
            inside = inside && blend[i] <= 1e-15 && blend[i + 1] >= -1e-15;
        }
        const bool pass = s > 0.0 && s < 1.0 && inside && worst <= tolerance;
        report.row(pass, "g.fillet_auto_scale", worst, tolerance,
                   format("s = %.6f; blend polygon inside the corner: %s; C3 by OCCT", s,
                          inside ? "yes" : "NO"));
    });
}

void check_intersect_detailed(Report& report) {
    guarded(report, "g.intersect_options_default", [&] {
        const BzjIntersectOptions o = bezjoin::intersect_options_default();
        // The defaults bezjoin.h documents.
        const bool pass = o.relative_distance_tolerance == 1e-9 && o.tangent_tolerance == 1e-6 &&
                          o.max_depth == 60 && o.max_box_pairs == 200000 && o.max_hits == 10000;
        report.row(pass, "g.intersect_options_default", pass ? 0.0 : 1.0, 0.0,
                   format("%g %g %zu %zu %zu", o.relative_distance_tolerance, o.tangent_tolerance,
                          o.max_depth, o.max_box_pairs, o.max_hits));
    });
    guarded(report, "g.intersect_detailed", [&] {
        // Three crossings (the same as intersect()), a touching point, an overlap.
        const Curve wave(2, 3, {0.0, -1.0, 1.0, 3.0, 2.0, -3.0, 3.0, 1.0});
        const Curve line(2, 1, {-0.5, 0.1, 3.5, -0.1});
        const auto hits = bezjoin::intersect_detailed(wave, line);
        const auto pairs = bezjoin::intersect(wave, line);
        bool pass = hits.size() == 3 && pairs.size() == 3;
        double worst = 0.0;
        Geom2dAPI_InterCurveCurve occ(occ_bezier2d(wave), occ_bezier2d(line), 1e-12);
        pass = pass && occ.NbPoints() == 3;
        for (std::size_t i = 0; i < hits.size() && pass; ++i) {
            const BzjIntersection& h = hits[i];
            pass = pass && h.kind == BZJ_INTERSECTION_CROSSING && h.u == pairs[i].first &&
                   h.v == pairs[i].second && h.u_end == h.u && h.v_end == h.v;
            double best = INFINITY;
            for (int j = 1; j <= occ.NbPoints(); ++j) {
                const IntRes2d_IntersectionPoint& point = occ.Intersector().Point(j);
                best = std::min(best, std::max(std::abs(point.ParamOnFirst() - h.u),
                                               std::abs(point.ParamOnSecond() - h.v)));
            }
            worst = std::max({worst, best, h.distance});
        }
        const Curve bowl(2, 2, {-1.0, 1.0, 0.0, -1.0, 1.0, 1.0});  // y = (1 - 2t)^2
        const Curve axis(2, 1, {-2.0, 0.0, 2.0, 0.0});
        const auto touch = bezjoin::intersect_detailed(bowl, axis);
        pass = pass && touch.size() == 1 && touch[0].kind == BZJ_INTERSECTION_TOUCHING &&
               std::abs(touch[0].u - 0.5) <= 1e-6;
        const Curve base(2, 1, {0.0, 0.0, 2.0, 0.0});
        const Curve over(2, 1, {3.0, 0.0, 1.0, 0.0});  // overlaps base on u in [0.5, 1], backwards
        const auto overlap = bezjoin::intersect_detailed(base, over);
        pass = pass && overlap.size() == 1 && overlap[0].kind == BZJ_INTERSECTION_OVERLAP &&
               std::abs(overlap[0].u - 0.5) <= 1e-9 && std::abs(overlap[0].u_end - 1.0) <= 1e-9 &&
               std::abs(overlap[0].v - 1.0) <= 1e-9 && std::abs(overlap[0].v_end - 0.5) <= 1e-9;
        report.row(pass && worst <= 1e-10, "g.intersect_detailed", worst, 1e-10,
                   "3 crossings = intersect() and OCCT's, 1 touching, 1 overlap [0.5, 1] -> [1, 0.5]");
    });
    expect_status(report, "g.intersect_detailed-options-reach", BZJ_ERR_ILL_CONDITIONED, [&] {
        const Curve wave(2, 3, {0.0, -1.0, 1.0, 3.0, 2.0, -3.0, 3.0, 1.0});
        const Curve line(2, 1, {-0.5, 0.1, 3.5, -0.1});
        BzjIntersectOptions o = bezjoin::intersect_options_default();
        o.max_hits = 2;  // three crossings
        (void)bezjoin::intersect_detailed(wave, line, o);
    });
}

void check_fillet_deviation(Report& report) {
    guarded(report, "g.fillet_deviation", [&] {
        const Curve p(2, 3, {0.0, 0.0, 0.8, 0.3, 1.5, -0.2, 2.2, 0.4});
        const Curve q(2, 3, {1.0, -1.0, 1.3, -0.2, 0.8, 0.6, 1.2, 1.4});
        const auto crossings = bezjoin::intersect(p, q);
        if (crossings.empty()) {
            throw std::runtime_error("no crossing");
        }
        const double u_star = crossings.front().first;
        const double v_star = crossings.front().second;
        bezjoin::DeviationFilletOptions opts;
        opts.max_deviation = 0.05;
        opts.setback_ratio = 1.5;
        opts.p_order = 2;
        opts.q_order = 2;
        const bezjoin::DeviationFillet f = bezjoin::fillet_deviation(p, q, opts);
        const BzjDeviationFilletReport& r = f.report;
        const Handle(Geom_BezierCurve) occ_p = occ_bezier(p);
        const Handle(Geom_BezierCurve) occ_q = occ_bezier(q);
        // OCCT's distance from the corner X to the blend: the reported deviation.
        const gp_Pnt corner = occ_p->Value(u_star);
        const Handle(Geom_BezierCurve) blend = occ_bezier(f.blend);
        GeomAPI_ProjectPointOnCurve projection(corner, blend);
        double occt_distance = std::min(corner.Distance(blend->StartPoint()),
                                        corner.Distance(blend->EndPoint()));
        if (projection.NbPoints() > 0) {
            occt_distance = std::min(occt_distance, projection.LowerDistance());
        }
        const double eps = opts.max_deviation;
        const bool window = r.deviation <= eps && r.deviation >= eps * (1.0 - 1e-9);
        const double distance_gap = std::abs(occt_distance - r.deviation) / eps;
        // Setbacks by OCCT's arc length; trims at the reported cuts.
        const double p_arc = GCPnts_AbscissaPoint::Length(GeomAdaptor_Curve(occ_p), r.u0, u_star, 1e-13);
        const double q_arc = GCPnts_AbscissaPoint::Length(GeomAdaptor_Curve(occ_q), v_star, r.v0, 1e-13);
        const double setback_gap = std::max({std::abs(p_arc - r.p_setback), std::abs(q_arc - r.q_setback),
                                             std::abs(r.q_setback - 1.5 * r.p_setback)});
        const double trim_gap = std::max(pole_difference(f.p_trimmed, occ_segment(occ_p, 0.0, r.u0)),
                                         pole_difference(f.q_trimmed, occ_segment(occ_q, r.v0, 1.0)));
        const double worst = std::max({distance_gap, setback_gap, trim_gap});
        report.row(window && worst <= 1e-9, "g.fillet_deviation", worst, 1e-9,
                   format("eps 0.05: deviation %.12f (OCCT projection %.12f) in [eps(1-1e-9), eps]: "
                          "%s; setbacks %.6f / %.6f by OCCT arc length",
                          r.deviation, occt_distance, window ? "yes" : "NO", r.p_setback, r.q_setback));
    });
    expect_status(report, "g.fillet_deviation-error-too-large", BZJ_ERR_INVALID_ARGUMENT, [&] {
        const Curve p(2, 1, {0.0, 0.0, 4.0, 4.0});
        const Curve q(2, 1, {0.0, 4.0, 4.0, 0.0});
        bezjoin::DeviationFilletOptions opts;
        opts.max_deviation = 100.0;
        opts.p_order = 1;
        opts.q_order = 1;
        (void)bezjoin::fillet_deviation(p, q, opts);
    });
}

// w. A closed wire rounded by radius (bzj_fillet_radius_chain), judged by
// OCCT: a plate outline of four lines and a cubic; at every join of the
// result GeomLProp_CLProps' unit tangent and curvature agree on both sides
// (G2); every corner's touching points are at the radius from the reported
// centre (bzj_fillet_radius_detailed on the corner alone gives the same
// centre), and OCCT's ChFi2d arc of the same radius at a line-line corner
// has that centre. Then the automatic-scale variants (vertex, chain,
// deviation): the blend of two long edges with a short setback stays in the
// corner's triangle, where the paper's scale 1 leaves it.
void check_radius_wire(Report& report) {
    const double radius = 1.5;
    std::vector<Curve> wire;
    wire.emplace_back(2, 1, std::vector<double>{0.0, 0.0, 12.0, 0.0});
    wire.emplace_back(2, 1, std::vector<double>{12.0, 0.0, 12.0, 6.0});
    wire.emplace_back(2, 3, std::vector<double>{12.0, 6.0, 9.0, 9.0, 4.0, 5.0, 0.0, 8.0});
    wire.emplace_back(2, 1, std::vector<double>{0.0, 8.0, 0.0, 0.0});
    guarded(report, "w.wire-G2-GeomLProp", [&] {
        const bezjoin::RadiusFilletChain rounded = bezjoin::fillet_radius_chain(wire, radius, 2, true);
        const std::size_t n = rounded.pieces.size();
        if (n != 2 * wire.size() || rounded.reports.size() != wire.size()) {
            throw std::runtime_error(format("%zu pieces, %zu reports", n, rounded.reports.size()));
        }
        double worst = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const Handle(Geom_Curve) a = occ_curve(rounded.pieces[i]);
            const Handle(Geom_Curve) b = occ_curve(rounded.pieces[(i + 1) % n]);
            const double ua = a->LastParameter();
            const double ub = b->FirstParameter();
            const LocalProps x = local_props(a, ua, false);
            const LocalProps y = local_props(b, ub, false);
            const double kappa_scale = std::max({1.0 / radius, x.kappa, y.kappa});
            worst = std::max({worst, a->Value(ua).Distance(b->Value(ub)) / 12.0,
                              (x.tangent - y.tangent).Magnitude(),
                              std::abs(x.kappa - y.kappa) / kappa_scale});
        }
        report.row(worst <= 1e-9, "w.wire-G2-GeomLProp", worst, 1e-9,
                   format("closed wire of 3 lines and a cubic, r %g: %zu joins, position / unit tangent / "
                          "curvature by GeomLProp_CLProps on both sides",
                          radius, n));
        // Corner 0 (line-line, 90 degrees at (12, 0)): the detailed single
        // fillet's centre, the chain's cuts, and ChFi2d's arc centre.
        const bezjoin::DetailedRadiusFillet one = bezjoin::fillet_radius_detailed(wire[0], wire[1], radius, 2);
        const BzjRadiusFilletReport& c0 = rounded.reports[0];
        const gp_Pnt vertex(12.0, 0.0, 0.0);
        const gp_Pnt a(0.0, 0.0, 0.0);
        const gp_Pnt b(12.0, 6.0, 0.0);
        const TopoDS_Vertex va = BRepBuilderAPI_MakeVertex(a);
        const TopoDS_Vertex vv = BRepBuilderAPI_MakeVertex(vertex);
        const TopoDS_Vertex vb = BRepBuilderAPI_MakeVertex(b);
        ChFi2d_FilletAPI api(BRepBuilderAPI_MakeEdge(va, vv).Edge(), BRepBuilderAPI_MakeEdge(vv, vb).Edge(),
                             gp_Pln(gp::XOY()));
        if (!api.Perform(radius) || api.NbResults(vertex) < 1) {
            throw std::runtime_error("ChFi2d_FilletAPI found no fillet");
        }
        TopoDS_Edge m1;
        TopoDS_Edge m2;
        const TopoDS_Edge arc = api.Result(vertex, m1, m2, -1);
        double first = 0.0;
        double last = 0.0;
        const Handle(Geom_Curve) curve = BRep_Tool::Curve(arc, first, last);
        const Handle(Geom_TrimmedCurve) trimmed = Handle(Geom_TrimmedCurve)::DownCast(curve);
        const Handle(Geom_Circle) circle =
            Handle(Geom_Circle)::DownCast(trimmed.IsNull() ? curve : trimmed->BasisCurve());
        if (circle.IsNull()) {
            throw std::runtime_error("ChFi2d_FilletAPI's fillet is not a circle");
        }
        const gp_Pnt occt_centre = circle->Location();
        const double centre_gap = occt_centre.Distance(gp_Pnt(one.arc_centre[0], one.arc_centre[1], 0.0));
        const double cut_gap = std::max(std::abs(c0.u0 - one.report.u0), std::abs(c0.v0 - one.report.v0));
        const double touch_gap = std::max(curve->Value(first).Distance(gp_Pnt(12.0 * c0.u0, 0.0, 0.0)),
                                          curve->Value(last).Distance(gp_Pnt(12.0, 6.0 * c0.v0, 0.0)));
        const double worst_corner = std::max({centre_gap, cut_gap, touch_gap});
        report.row(worst_corner <= 1e-12, "w.corner-vs-ChFi2d", worst_corner, 1e-12,
                   format("corner 0: centre ours (%.6f, %.6f), ChFi2d (%.6f, %.6f); the arc's ends are the "
                          "chain's cuts; arc deviation of the G2 blend %.4f",
                          one.arc_centre[0], one.arc_centre[1], occt_centre.X(), occt_centre.Y(),
                          one.report.arc_deviation));
    });
    // The automatic scales: two lines 40 and 20 long meeting at the origin
    // at a right angle, setback 2 (chain: an open L of the same lines).
    const Curve p(2, 1, {-40.0, 0.0, 0.0, 0.0});
    const Curve q(2, 1, {0.0, 0.0, 0.0, 20.0});
    auto in_corner = [](const Curve& blend, double setback) {
        double worst = 0.0;  // how far a control point lies outside the triangle
        const std::vector<double> pts = blend.points();
        for (std::size_t i = 0; i + 1 < pts.size(); i += 2) {
            const double x = pts[i];
            const double y = pts[i + 1];
            worst = std::max({worst, x, -y, y - x - setback});
        }
        return worst;
    };
    guarded(report, "w.auto-scale-stays-in-corner", [&] {
        bezjoin::FilletOptions o;
        o.p_setback = 2.0;
        o.q_setback = 2.0;
        o.p_order = 2;
        o.q_order = 2;
        const double paper = in_corner(bezjoin::fillet_vertex(p, q, o, 1e-9).blend, 2.0);
        const bezjoin::AutoScaledFillet v = bezjoin::fillet_vertex_auto_scale(p, q, o, 1e-9);
        const bezjoin::AutoScaledFilletChain c = bezjoin::fillet_chain_auto_scale({&p, &q}, o, false);
        bezjoin::DeviationFilletOptions d;
        d.max_deviation = 0.1;
        d.p_order = 2;
        d.q_order = 2;
        const Curve pc(2, 1, {-40.0, 0.0, 10.0, 0.0});
        const Curve qc(2, 1, {0.0, -10.0, 0.0, 20.0});
        double s = 0.0;
        const bezjoin::DeviationFillet dev = bezjoin::fillet_deviation_auto_scale(pc, qc, d, s);
        const double worst = std::max({in_corner(v.blend, 2.0), in_corner(c.pieces[1], 2.0),
                                       in_corner(dev.blend, dev.report.p_setback)});
        const bool paper_leaves = paper > 1.0;
        report.row(worst <= 1e-12 && paper_leaves, "w.auto-scale-stays-in-corner", std::max(worst, 0.0), 1e-12,
                   format("control points outside the corner's triangle: scale 1 by %.3f; automatic (vertex s %.4g, "
                          "chain s %.4g, deviation s %.4g, setback %.4f) by at most %.1e",
                          paper, v.scale, c.scales.at(0), s, dev.report.p_setback, std::max(worst, 0.0)));
    });
    // The balanced scales: lines 1000 and 10 long at a right angle, setback 1, cut at the
    // same points as lines 10 and 10; only the edges' speeds differ. The balanced blend
    // is the same curve (peak curvature by OCCT's GeomLProp), both its ends at one speed
    // (OCCT's DN); the one-s automatic scale makes a near-kink at the short edge.
    guarded(report, "w.balanced-scale-ignores-edge-length", [&] {
        const Curve long_edge(2, 1, {-1000.0, 0.0, 0.0, 0.0});
        const Curve short_edge(2, 1, {-10.0, 0.0, 0.0, 0.0});
        const Curve up(2, 1, {0.0, 0.0, 0.0, 10.0});
        bezjoin::FilletOptions o;
        o.p_setback = 1.0;
        o.q_setback = 1.0;
        o.p_order = 2;
        o.q_order = 2;
        auto peak = [](const Curve& blend) {
            const Handle(Geom_BezierCurve) occ = occ_bezier(blend);
            double most = 0.0;
            for (int i = 0; i <= 400; ++i) {
                most = std::max(most, curvature(Handle(Geom_Curve)(occ), i / 400.0));
            }
            return most;
        };
        const bezjoin::BalancedFillet equal = bezjoin::fillet_vertex_balanced_scale(short_edge, up, o, 0.0);
        const bezjoin::BalancedFillet unequal = bezjoin::fillet_vertex_balanced_scale(long_edge, up, o, 0.0);
        const bezjoin::AutoScaledFillet automatic = bezjoin::fillet_vertex_auto_scale(long_edge, up, o, 0.0);
        const Handle(Geom_BezierCurve) occ = occ_bezier(unequal.blend);
        const double start = occ->DN(0.0, 1).Magnitude();
        const double end = occ->DN(1.0, 1).Magnitude();
        const double speeds = std::abs(start - end) / std::max(start, end);
        const double peaks = std::abs(peak(unequal.blend) - peak(equal.blend)) / peak(equal.blend);
        // The same through connect and the crossing fillet: the blend of the cut lines.
        bezjoin::ConnectOptions c;
        c.p_order = 2;
        c.q_order = 2;
        const bezjoin::BalancedConnection joined =
            bezjoin::connect_balanced_scale(long_edge, 0.999, up, 0.1, c);
        const Curve crossing_p(2, 1, {-1000.0, 0.0, 5.0, 0.0});
        const Curve crossing_q(2, 1, {0.0, -5.0, 0.0, 10.0});
        const bezjoin::BalancedFillet crossing = bezjoin::fillet_balanced_scale(crossing_p, crossing_q, o);
        double apart = 0.0;
        const std::vector<double> a = joined.curve.points();
        const std::vector<double> b = crossing.blend.points();
        const std::vector<double> e = equal.blend.points();
        for (std::size_t i = 0; i < e.size(); ++i) {
            apart = std::max({apart, std::abs(a[i] - e[i]), std::abs(b[i] - e[i])});
        }
        // A closed 1000 x 10 rectangle (fillet_chain_balanced_scale): each corner's
        // blend is the 10 x 10 square's at that corner.
        auto rectangle = [](double w, double h) {
            const double c[4][2] = {{0.0, 0.0}, {w, 0.0}, {w, h}, {0.0, h}};
            std::vector<Curve> sides;
            for (int i = 0; i < 4; ++i) {
                sides.emplace_back(2, 1, std::vector<double>{c[i][0], c[i][1], c[(i + 1) % 4][0],
                                                             c[(i + 1) % 4][1]});
            }
            return sides;
        };
        const std::vector<Curve> long_sides = rectangle(1000.0, 10.0);
        const std::vector<Curve> square_sides = rectangle(10.0, 10.0);
        const bezjoin::BalancedFilletChain long_chain = bezjoin::fillet_chain_balanced_scale(long_sides, o, true);
        const bezjoin::BalancedFilletChain square_chain = bezjoin::fillet_chain_balanced_scale(square_sides, o, true);
        for (int i = 0; i < 4; ++i) {
            const std::vector<double> lp = long_chain.pieces.at(2 * i + 1).points();
            const std::vector<double> sp = square_chain.pieces.at(2 * i + 1).points();
            const std::vector<double> lc = long_sides[(i + 1) % 4].points();
            const std::vector<double> sc = square_sides[(i + 1) % 4].points();
            for (std::size_t k = 0; k < lp.size(); ++k) {
                apart = std::max(apart, std::abs((lp[k] - lc[k % 2]) - (sp[k] - sc[k % 2])));
            }
        }
        const double worst = std::max({speeds, peaks, apart});
        const double kink = peak(automatic.blend) / peak(equal.blend);
        report.row(worst <= 1e-9 && kink > 10.0, "w.balanced-scale-ignores-edge-length", worst, 1e-9,
                   format("peak curvature: balanced %.4f on lines 1000/10, %.4f on 10/10; one-s automatic "
                          "%.4g (%.0fx); end speeds %.6f / %.6f; connect, crossing fillet and the 1000 x 10 "
                          "rectangle's chain give the same blend to %.1e",
                          peak(unequal.blend), peak(equal.blend), peak(automatic.blend), kink, start, end, apart));
    });
}

void check_fillet_chain(Report& report, StepScene& scene) {
    guarded(report, "g.fillet_chain", [&] {
        // A closed curved triangle: three bulged cubic sides meeting end to end.
        const double vertex[3][2] = {{0.0, 0.0}, {4.0, 0.0}, {1.0, 3.0}};
        std::vector<Curve> sides;
        for (int i = 0; i < 3; ++i) {
            sides.emplace_back(2, 3, bulged_side(vertex[i], vertex[(i + 1) % 3], -0.08));
        }
        bezjoin::FilletOptions opts;
        opts.p_setback = 0.5;
        opts.q_setback = 0.4;
        opts.p_order = 2;
        opts.q_order = 2;
        const std::vector<Curve> closed = bezjoin::fillet_chain(sides, opts, true);
        const std::vector<Curve> open = bezjoin::fillet_chain({&sides[0], &sides[1], &sides[2]}, opts);
        bool pass = closed.size() == 6 && open.size() == 5;
        double worst = pass ? 0.0 : INFINITY;
        if (pass) {
            // Trimmed side i (piece 2i) is side i on [a, b]: its knot interval
            // is b - a; the blends' intervals are the scales (1).
            std::vector<const Curve*> pieces;
            std::vector<double> widths;
            for (int i = 0; i < 7; ++i) {
                const Curve& piece = closed[static_cast<std::size_t>(i % 6)];
                pieces.push_back(&piece);
                if (i % 2 == 0) {
                    const double* a = vertex[(i / 2) % 3];
                    const double* b = vertex[(i / 2 + 1) % 3];
                    widths.push_back(chord_parameter(a, b, piece.eval(1.0)) -
                                     chord_parameter(a, b, piece.eval(0.0)));
                } else {
                    widths.push_back(1.0);
                }
            }
            worst = chain_defect(pieces, widths, 2, 1e-9);  // the closing join included
            // The open chain: the same corners 0 and 1, side 0 kept from its start.
            const std::vector<double> start = open.front().eval(0.0);
            const std::vector<double> end = open.back().eval(1.0);
            worst = std::max({worst, std::hypot(start[0] - vertex[0][0], start[1] - vertex[0][1]),
                              std::hypot(end[0] - vertex[0][0], end[1] - vertex[0][1])});
            for (std::size_t i = 1; i < 4; ++i) {
                worst = std::max(worst, pole_difference(open[i], occ_bezier(closed[i])));
            }
            for (const Curve& piece : closed) {
                scene.add(piece, gp_Vec(0.0, 17.0, 0.0));
            }
        }
        report.row(pass && worst <= 1e-9, "g.fillet_chain", worst, 1e-9,
                   "closed triangle of cubics: 6 pieces C2 by OCCT at every join incl. the closing one; "
                   "open: 5 pieces, same inner corners");
    });
    expect_status(report, "g.fillet_chain-error-one-curve", BZJ_ERR_INVALID_ARGUMENT, [&] {
        const Curve p(2, 1, {0.0, 0.0, 4.0, 4.0});
        bezjoin::FilletOptions opts;
        opts.p_setback = 0.5;
        opts.q_setback = 0.5;
        (void)bezjoin::fillet_chain({&p}, opts);
    });
}

void check_lagrange_degree(Report& report) {
    guarded(report, "g.lagrange_spline_degree", [&] {
        // Degree 5, C^2 on a helix: every given point at its parameter on
        // OCCT's B-spline, and C^2 by OCCT at every node.
        const std::size_t dim = 3;
        const std::size_t degree = 5;
        const std::vector<double> params = {0.0, 0.8, 1.5, 2.4, 3.0};
        auto helix = [](double x) { return gp_Pnt(std::cos(x), std::sin(x), 0.3 * x); };
        std::vector<double> nodes;
        std::vector<double> start_inner;
        std::vector<double> free_inner;
        std::vector<double> given_at = params;
        for (double x : params) {
            const gp_Pnt pt = helix(x);
            nodes.insert(nodes.end(), {pt.X(), pt.Y(), pt.Z()});
        }
        for (std::size_t j = 1; j < degree; ++j) {  // all inner points of segment 0
            const double x = params[0] + (params[1] - params[0]) * j / double(degree);
            const gp_Pnt pt = helix(x);
            start_inner.insert(start_inner.end(), {pt.X(), pt.Y(), pt.Z()});
            given_at.push_back(x);
        }
        for (std::size_t i = 1; i + 1 < params.size(); ++i) {  // u = 3/5, 4/5 of the others
            for (double f : {3.0 / 5.0, 4.0 / 5.0}) {
                const double x = params[i] + (params[i + 1] - params[i]) * f;
                const gp_Pnt pt = helix(x);
                free_inner.insert(free_inner.end(), {pt.X(), pt.Y(), pt.Z()});
                given_at.push_back(x);
            }
        }
        const std::vector<Curve> segments = bezjoin::lagrange_spline_degree(
            dim, degree, 2, 0, nodes, params, start_inner, free_inner);
        std::vector<const Curve*> pieces;
        std::vector<double> intervals;
        bool degrees = segments.size() == params.size() - 1;
        for (std::size_t i = 0; i < segments.size(); ++i) {
            pieces.push_back(&segments[i]);
            intervals.push_back(params[i + 1] - params[i]);
            degrees = degrees && segments[i].degree() == degree;
        }
        const Chain chain = make_chain(pieces, intervals, params[0]);
        double miss = chain.pole_gap;
        for (double x : given_at) {
            miss = std::max(miss, chain.curve->Value(x).Distance(helix(x)) / chain.size);
        }
        double jump = 0.0;
        for (int index = 2; index < static_cast<int>(chain.knots.size()); ++index) {
            const JoinVerdict verdict = judge_join(chain, index, 2, 1e-9 * chain.size);
            jump = std::max(jump, verdict.removable ? verdict.jump : INFINITY);
        }
        const double worst = std::max(miss, jump);
        report.row(degrees && worst <= 1e-9, "g.lagrange_spline_degree", worst, 1e-9,
                   format("degree 5 C2: %zu given points on OCCT's B-spline (miss %.1e), C2 jump %.1e",
                          given_at.size(), miss, jump));
        // BACKWARD, degree 3, C^1: both inner points of the last segment are
        // given, then the u = 1/3 point of every earlier one.
        const std::size_t last = params.size() - 2;
        std::vector<double> cubic_start;
        std::vector<double> cubic_free;
        std::vector<double> back_given_at = params;
        for (double f : {1.0 / 3.0, 2.0 / 3.0}) {
            const double x = params[last] + (params[last + 1] - params[last]) * f;
            const gp_Pnt pt = helix(x);
            cubic_start.insert(cubic_start.end(), {pt.X(), pt.Y(), pt.Z()});
            back_given_at.push_back(x);
        }
        for (std::size_t i = 0; i < last; ++i) {
            const double x = params[i] + (params[i + 1] - params[i]) / 3.0;
            const gp_Pnt pt = helix(x);
            cubic_free.insert(cubic_free.end(), {pt.X(), pt.Y(), pt.Z()});
            back_given_at.push_back(x);
        }
        const std::vector<Curve> backward = bezjoin::lagrange_spline_degree(
            dim, 3, 1, BZJ_LAGRANGE_BACKWARD, nodes, params, cubic_start, cubic_free);
        std::vector<const Curve*> back_pieces;
        for (const Curve& c : backward) {
            back_pieces.push_back(&c);
        }
        const Chain back_chain = make_chain(back_pieces, intervals, params[0]);
        double back_miss = back_chain.pole_gap;
        for (double x : back_given_at) {
            back_miss = std::max(back_miss, back_chain.curve->Value(x).Distance(helix(x)) / back_chain.size);
        }
        const double back = std::max(back_miss, chain_defect(back_pieces, intervals, 1, 1e-9));
        report.row(backward.size() == 4 && back <= 1e-9, "g.lagrange_spline_degree-backward", back, 1e-9,
                   format("degree 3, C1, BZJ_LAGRANGE_BACKWARD: %zu given points on OCCT's curve, C1 by OCCT",
                          back_given_at.size()));
    });
    guarded(report, "g.lagrange_spline_degree-size-check", [&] {
        try {
            (void)bezjoin::lagrange_spline_degree(2, 4, 1, 0, {0.0, 0.0, 1.0, 0.0, 2.0, 1.0}, {},
                                                  {0.3, 0.1}, {});  // start_inner needs 3 points
            report.fail("g.lagrange_spline_degree-size-check", "no exception for a short start_inner");
        } catch (const std::invalid_argument& e) {
            const bool ok = std::strstr(e.what(), "start_inner") != nullptr;
            report.row(ok, "g.lagrange_spline_degree-size-check", ok ? 0.0 : 1.0, 0.0, e.what());
        }
    });
    expect_status(report, "g.lagrange_spline_degree-error-degree", BZJ_ERR_INVALID_ARGUMENT, [&] {
        (void)bezjoin::lagrange_spline_degree(2, 6, 1, 0, {0.0, 0.0, 1.0, 0.0}, {}, {0.3, 0.1}, {});
    });
}

void check_merge_degree_and_chain(Report& report) {
    const double tolerance = 1e-12;
    guarded(report, "g.merge_to_degree", [&] {
        const Curve p(3, 3, {0.0, 0.0, 0.0, 0.4, 0.5, 0.1, 0.9, 0.7, 0.2, 1.4, 0.75, 0.2});
        const Curve q(3, 3, {1.4, 0.75, 0.2, 1.9, 0.8, 0.2, 2.4, 0.5, 0.1, 2.8, 0.0, 0.0});
        bezjoin::MergeOptions opts;
        opts.metric = BZJ_METRIC_L2;
        opts.split = BZJ_SPLIT_POLYGON;
        const bezjoin::Merge m6 = bezjoin::merge_to_degree(p, q, opts, 6);
        const bezjoin::Merge m3 = bezjoin::merge(p, q, opts);
        const double mu = m6.report.mu;
        const Handle(Geom_BezierCurve) r = occ_bezier(m6.merged);
        const double gap = std::max(pole_difference(m6.p_hat, occ_segment(r, 0.0, mu)),
                                    pole_difference(m6.q_hat, occ_segment(r, mu, 1.0)));
        const bool pass = m6.merged.degree() == 6 && mu == m3.report.mu &&
                          m6.report.metric_value <= m3.report.metric_value * (1.0 + 1e-12) &&
                          gap <= tolerance;
        report.row(pass, "g.merge_to_degree", gap, tolerance,
                   format("degree 6: pieces = OCCT Segment at mu = %.6f; metric %.3e <= degree 3's %.3e",
                          mu, m6.report.metric_value, m3.report.metric_value));
    });
    expect_status(report, "g.merge_to_degree-error-below", BZJ_ERR_INVALID_ARGUMENT, [&] {
        const Curve p(2, 3, {0.0, 0.0, 1.0, 1.0, 2.0, 1.0, 3.0, 0.0});
        (void)bezjoin::merge_to_degree(p, p, bezjoin::MergeOptions{}, 2);
    });
    guarded(report, "g.merge_chain", [&] {
        // Three pieces of one cubic, breakpoints given where it was cut: the
        // merge gives the cubic back, unchanged pieces, zero deviation.
        const Curve original(2, 3, {0.0, 0.0, 1.0, 2.0, 3.0, 2.5, 4.0, 0.0});
        const std::vector<Curve> parts = [&] {
            std::vector<Curve> out;
            out.push_back(original.segment(0.0, 0.2));
            out.push_back(original.segment(0.2, 0.7));
            out.push_back(original.segment(0.7, 1.0));
            return out;
        }();
        bezjoin::ChainMergeOptions opts;
        opts.metric = BZJ_METRIC_L2;
        opts.split = BZJ_CHAIN_SPLIT_GIVEN;
        opts.breakpoints = {0.2, 0.7};
        const bezjoin::ChainMerge back = bezjoin::merge_chain(parts, opts);
        double worst = pole_difference(back.merged, occ_bezier(original));
        bool pass = back.pieces.size() == 3 && back.breakpoints.size() == 4 &&
                    back.breakpoints == std::vector<double>({0.0, 0.2, 0.7, 1.0});
        for (std::size_t j = 0; j < back.pieces.size() && pass; ++j) {
            worst = std::max(worst, pole_difference(back.pieces[j], occ_bezier(parts[j])));
        }
        worst = std::max(worst, back.report.max_deviation);
        report.row(pass && worst <= 1e-9, "g.merge_chain-gives-back", worst, 1e-9,
                   "3 pieces of a cubic merge back into it (breakpoints 0.2, 0.7)");

        // Unrelated curves, uniform split, degree 5, ends fixed, a keep flag and
        // a keep point: the pieces are OCCT's Segments of the merged curve.
        const Curve a(2, 3, {0.0, 0.0, 1.0, 1.0, 2.0, 1.0, 3.0, 0.0});
        const Curve b(2, 3, {3.1, 0.1, 4.0, -1.0, 5.0, -1.0, 6.0, 0.5});
        const Curve c(2, 2, {6.0, 0.4, 7.0, 1.5, 8.0, 1.0});
        bezjoin::ChainMergeOptions free;
        free.degree = 5;
        free.fix_ends = true;
        free.keep = {false, false, false};
        free.keep_points = {bezjoin::ChainKeepPoint{1, 0.5, 1}};
        const bezjoin::ChainMerge m = bezjoin::merge_chain({&a, &b, &c}, free);
        const Handle(Geom_BezierCurve) r = occ_bezier(m.merged);
        double piece_gap = 0.0;
        for (std::size_t j = 0; j < 3; ++j) {
            piece_gap = std::max(piece_gap, pole_difference(m.pieces[j],
                                                            occ_segment(r, m.breakpoints[j], m.breakpoints[j + 1])));
        }
        // The kept point of b: the piece has b's value and first derivative at 0.5.
        const std::vector<double> kept = m.pieces[1].eval(0.5, 1);
        const std::vector<double> wanted = b.eval(0.5, 1);
        double kept_gap = 0.0;
        for (std::size_t i = 0; i < kept.size(); ++i) {
            kept_gap = std::max(kept_gap, std::abs(kept[i] - wanted[i]) / std::max(1.0, max_abs(wanted)));
        }
        const bool uniform = std::abs(m.breakpoints[1] - 1.0 / 3.0) <= 1e-15 &&
                             std::abs(m.breakpoints[2] - 2.0 / 3.0) <= 1e-15;
        const double free_worst = std::max(piece_gap, kept_gap);
        report.row(m.merged.degree() == 5 && uniform && free_worst <= 1e-9, "g.merge_chain", free_worst,
                   1e-9,
                   format("degree 5, uniform split: pieces = OCCT Segments; kept point miss %.1e; "
                          "deviation %.3e",
                          kept_gap, m.report.max_deviation));
    });
    guarded(report, "g.merge_chain-keep-size-check", [&] {
        const Curve a(2, 1, {0.0, 0.0, 1.0, 0.0});
        bezjoin::ChainMergeOptions opts;
        opts.keep = {true};
        try {
            (void)bezjoin::merge_chain({&a, &a}, opts);
            report.fail("g.merge_chain-keep-size-check", "no exception for 1 keep flag, 2 curves");
        } catch (const std::invalid_argument& e) {
            const bool ok = std::strstr(e.what(), "keep") != nullptr;
            report.row(ok, "g.merge_chain-keep-size-check", ok ? 0.0 : 1.0, 0.0, e.what());
        }
    });
    expect_status(report, "g.merge_chain-error-breakpoints", BZJ_ERR_INVALID_ARGUMENT, [&] {
        const Curve a(2, 1, {0.0, 0.0, 1.0, 0.0});
        bezjoin::ChainMergeOptions opts;
        opts.split = BZJ_CHAIN_SPLIT_GIVEN;
        opts.breakpoints = {0.6, 0.4};
        (void)bezjoin::merge_chain({&a, &a, &a}, opts);
    });
}

// ---------------------------------------------------------------- B-spline merge (issue 17)
//
// Rows "n.merge-...": bzj_merge of two polynomial cubic B-splines built by
// OCCT as two adjacent edges (4 spans each, non-uniform knots, a double knot
// in P; P's last pole is Q's first pole, with a tangent kink of about 5
// degrees there). Setting: L2 metric, optimal mu, ends fixed. R must carry
// P's interior knots mapped into (0, mu) and Q's into (mu, 1), none at mu
// (a. knots), evaluate as OCCT's Geom_BSplineCurve of it (b.), be C^3 (C^inf)
// across mu by OCCT's RemoveKnot judge on p_hat + q_hat joined in R's
// parameter (c.); its deviation from P-then-Q is set beside OCCT's own join
// of P and Q (exact, but C^0 at the join) (d.), both timed (e.), and a
// B-spline split at a non-knot parameter merges back into itself (f.; and
// cut in three, through bzj_merge_chain).

// A polynomial B-spline of OCCT from poles, distinct knots and multiplicities.
Handle(Geom_BSplineCurve) occ_polynomial(const std::vector<gp_Pnt>& poles, const std::vector<double>& knots,
                                         const std::vector<int>& mults, int degree) {
    TColgp_Array1OfPnt p(1, static_cast<int>(poles.size()));
    for (std::size_t i = 0; i < poles.size(); ++i) {
        p(static_cast<int>(i) + 1) = poles[i];
    }
    return new Geom_BSplineCurve(p, occ_reals(knots), occ_ints(mults), degree);
}

// max |coordinate| of the poles, at least 1: the scale of "relative".
double pole_size(const Handle(Geom_BSplineCurve)& c) {
    double size = 1.0;
    for (int i = 1; i <= c->NbPoles(); ++i) {
        const gp_Pnt p = c->Pole(i);
        size = std::max({size, std::abs(p.X()), std::abs(p.Y()), std::abs(p.Z())});
    }
    return size;
}

// A copy of `c` with its domain mapped affinely onto [u1, u2] (BSplCLib::Reparametrize).
Handle(Geom_BSplineCurve) occ_reparametrized(const Handle(Geom_BSplineCurve)& c, double u1, double u2) {
    Handle(Geom_BSplineCurve) copy = Handle(Geom_BSplineCurve)::DownCast(c->Copy());
    TColStd_Array1OfReal knots(1, copy->NbKnots());
    copy->Knots(knots);
    BSplCLib::Reparametrize(u1, u2, knots);
    copy->SetKnots(knots);
    return copy;
}

// The index of the distinct knot of `c` nearest to u.
int nearest_knot(const Handle(Geom_BSplineCurve)& c, double u) {
    int best = 1;
    for (int i = 2; i <= c->NbKnots(); ++i) {
        if (std::abs(c->Knot(i) - u) < std::abs(c->Knot(best) - u)) {
            best = i;
        }
    }
    return best;
}

// judge_join's Chain view of an OCCT B-spline.
Chain chain_of(const Handle(Geom_BSplineCurve)& c) {
    Chain chain;
    chain.curve = c;
    chain.degree = c->Degree();
    chain.size = pole_size(c);
    for (int i = 1; i <= c->NbKnots(); ++i) {
        chain.knots.push_back(c->Knot(i));
    }
    return chain;
}

void check_bspline_merge(Report& report, std::vector<Timing>& timings, const Options& options) {
    std::mt19937_64 rng(17017);
    const int degree = 3;
    const double tolerance = 1e-12;
    // Two adjacent edges: P on [2, 5.5] (8 poles, knots 2.7, 3.9 (double), 4.6),
    // Q on [-1, 1.5] (7 poles, knots -0.4, 0.3, 0.8); P's last pole = Q's first.
    const gp_Pnt corner(4.3, 0.65, 0.3);
    const Handle(Geom_BSplineCurve) occ_p = occ_polynomial(
        {gp_Pnt(0.0, 0.0, 0.0), gp_Pnt(0.5, 0.4, 0.05), gp_Pnt(1.1, 0.9, 0.1), gp_Pnt(1.8, 1.1, 0.2),
         gp_Pnt(2.5, 1.0, 0.25), gp_Pnt(3.1, 0.8, 0.3), gp_Pnt(3.7, 0.7, 0.3), corner},
        {2.0, 2.7, 3.9, 4.6, 5.5}, {4, 1, 2, 1, 4}, degree);
    const Handle(Geom_BSplineCurve) occ_q = occ_polynomial(
        {corner, gp_Pnt(4.9, 0.55, 0.32), gp_Pnt(5.6, 0.5, 0.3), gp_Pnt(6.2, 0.7, 0.2), gp_Pnt(6.8, 1.0, 0.1),
         gp_Pnt(7.3, 1.2, 0.05), gp_Pnt(7.9, 1.1, 0.0)},
        {-1.0, -0.4, 0.3, 0.8, 1.5}, {4, 1, 1, 1, 4}, degree);
    const double a_p = occ_p->FirstParameter();
    const double b_p = occ_p->LastParameter();
    const double a_q = occ_q->FirstParameter();
    const double b_q = occ_q->LastParameter();
    const double size = std::max(pole_size(occ_p), pole_size(occ_q));
    bezjoin::MergeOptions opts;
    opts.metric = BZJ_METRIC_L2;
    opts.split = BZJ_SPLIT_OPTIMAL;
    opts.fix_ends = true;
    const std::string setting = "L2 metric, optimal mu, ends fixed";

    std::unique_ptr<Curve> p;
    std::unique_ptr<Curve> q;
    std::unique_ptr<bezjoin::Merge> m;
    Handle(Geom_BSplineCurve) occ_r;
    bool r_has_no_knot_at_mu = false;
    guarded(report, "n.merge-knots", [&] {
        p.reset(new Curve(ours_from_occ(occ_p, 3)));
        q.reset(new Curve(ours_from_occ(occ_q, 3)));
        m.reset(new bezjoin::Merge(bezjoin::merge(*p, *q, opts)));
        const double mu = m->report.mu;
        occ_r = occ_bspline(m->merged);
        // Expected from OCCT's own P and Q: 0, P's interior knots mapped into
        // (0, mu), Q's into (mu, 1), 1; multiplicities kept.
        std::vector<double> knots = {0.0};
        std::vector<int> mults = {degree + 1};
        for (int i = 2; i < occ_p->NbKnots(); ++i) {
            knots.push_back(mu * ((occ_p->Knot(i) - a_p) / (b_p - a_p)));
            mults.push_back(occ_p->Multiplicity(i));
        }
        for (int i = 2; i < occ_q->NbKnots(); ++i) {
            knots.push_back(mu + (1.0 - mu) * ((occ_q->Knot(i) - a_q) / (b_q - a_q)));
            mults.push_back(occ_q->Multiplicity(i));
        }
        knots.push_back(1.0);
        mults.push_back(degree + 1);
        bool same = occ_r->NbKnots() == static_cast<int>(knots.size()) && occ_r->Degree() == degree &&
                    !occ_r->IsRational() && !m->merged.is_rational() &&
                    occ_r->NbPoles() == occ_p->NbPoles() + occ_q->NbPoles() - degree - 1;
        double worst = 0.0;
        std::string r_knots;
        for (int i = 1; same && i <= occ_r->NbKnots(); ++i) {
            same = occ_r->Multiplicity(i) == mults[i - 1];
            worst = std::max(worst, std::abs(occ_r->Knot(i) - knots[i - 1]));
            r_knots += format("%s%.6f(%d)", i == 1 ? "" : " ", occ_r->Knot(i), occ_r->Multiplicity(i));
        }
        // Nothing at mu: mu lies strictly inside one span (LocateU gives two
        // different knots), the nearest knot some distance away.
        int i1 = 0;
        int i2 = 0;
        occ_r->LocateU(mu, 0.0, i1, i2);
        const double nearest = std::abs(occ_r->Knot(nearest_knot(occ_r, mu)) - mu);
        r_has_no_knot_at_mu = i1 != i2 && i2 == i1 + 1 && i1 == occ_p->NbKnots() - 1 && nearest > 0.0;
        // p_hat / q_hat on P's / Q's own knots (flat sequences).
        double own = 0.0;
        auto own_knots = [&](const Curve& piece, const Handle(Geom_BSplineCurve)& input) {
            const std::vector<double> flat = piece.knots();
            const TColStd_Array1OfReal& sequence = input->KnotSequence();
            if (static_cast<int>(flat.size()) != sequence.Length()) {
                return false;
            }
            for (std::size_t i = 0; i < flat.size(); ++i) {
                own = std::max(own, std::abs(flat[i] - sequence(sequence.Lower() + static_cast<int>(i))));
            }
            return true;
        };
        same = same && own_knots(m->p_hat, occ_p) && own_knots(m->q_hat, occ_q);
        worst = std::max(worst, own);
        const bool pass = same && r_has_no_knot_at_mu && worst <= 1e-14;
        report.row(pass, "n.merge-knots", worst, 1e-14,
                   format("%s: mu = %.6f; R (OCCT knots(mults)): %s; %d poles = %d + %d - 4; mu inside span "
                          "[%.6f, %.6f], nearest knot %.3e away; p_hat/q_hat on P's/Q's own knots (max diff %.1e)",
                          setting.c_str(), mu, r_knots.c_str(), occ_r->NbPoles(), occ_p->NbPoles(),
                          occ_q->NbPoles(), occ_r->Knot(i1), occ_r->Knot(i2), nearest, own));
    });
    auto need_merge = [&](const char* name) {
        if (!m) {
            report.fail(name, "no merge (see n.merge-knots)");
            return false;
        }
        return true;
    };

    // b. OCCT's evaluation of R against ours.
    if (need_merge("n.merge-R-eval-vs-OCCT")) {
        guarded(report, "n.merge-R-eval-vs-OCCT", [&] {
            const double r_size = pole_size(occ_r);
            std::vector<double> ts;
            for (int i = 0; i <= 4000; ++i) {
                ts.push_back(i / 4000.0);
            }
            for (int i = 1; i <= occ_r->NbKnots(); ++i) {
                ts.push_back(occ_r->Knot(i));
            }
            ts.push_back(m->report.mu);
            const std::vector<double> ours = m->merged.eval_many(ts, 0);
            double worst = 0.0;
            for (std::size_t i = 0; i < ts.size(); ++i) {
                worst = std::max(worst, point3(&ours[3 * i], 3).Distance(occ_r->Value(ts[i])) / r_size);
            }
            const JetComparison e = compare_jets(m->merged, occ_r, rng, options.quick ? 60 : 400);
            const bool pass = worst <= tolerance && e.worst() <= tolerance;
            report.row(pass, "n.merge-R-eval-vs-OCCT", std::max(worst, e.worst()), tolerance,
                       format("%zu parameters: max |ours - OCCT Value| / size %.1e; jets (%zu samples incl. %zu "
                              "knots both sides) orders 0-3: %.1e %.1e %.1e %.1e, left of knots %.1e",
                              ts.size(), worst, e.samples, e.knots, e.error[0], e.error[1], e.error[2], e.error[3],
                              e.left));
        });
    }

    // c. Continuity at mu by OCCT: p_hat on [0, mu] and q_hat on [mu, 1]
    // (BSplCLib::Reparametrize) joined by GeomConvert_CompCurveToBSplineCurve
    // (no ratio, MinM = degree: a knot of multiplicity 3 at mu); RemoveKnot
    // must take it away entirely (C^3, i.e. one cubic across mu).
    if (need_merge("n.merge-join-C3-by-OCCT")) {
        guarded(report, "n.merge-join-C3-by-OCCT", [&] {
            const double mu = m->report.mu;
            const Handle(Geom_BSplineCurve) p_hat = occ_bspline(m->p_hat);
            const Handle(Geom_BSplineCurve) q_hat = occ_bspline(m->q_hat);
            const double join_tolerance = 1e-9 * size;
            GeomConvert_CompCurveToBSplineCurve join(occ_reparametrized(p_hat, 0.0, mu));
            const bool added = join.Add(occ_reparametrized(q_hat, mu, 1.0), join_tolerance, true, false, degree);
            const Handle(Geom_BSplineCurve) joined = join.BSplineCurve();
            const int index = nearest_knot(joined, mu);
            const int multiplicity = joined->Multiplicity(index);
            const Chain chain = chain_of(joined);
            const JoinVerdict verdict = judge_join(chain, index, degree, 1e-9 * size);
            // The joined pieces are R (OCCT evaluating both).
            double joined_gap = 0.0;
            for (int i = 0; i <= 1000; ++i) {
                const double t = i / 1000.0;
                joined_gap = std::max(joined_gap, joined->Value(t).Distance(occ_r->Value(t)) / size);
            }
            // Derivatives 1..3 at the ends of p_hat and q_hat (OCCT's DN, in
            // their own parameters) scaled into R's parameter, against each
            // other and R's DN at mu.
            double derivative_gap = 0.0;
            std::string orders;
            for (int k = 1; k <= degree; ++k) {
                const gp_Vec left = p_hat->DN(b_p, k) * std::pow((b_p - a_p) / mu, k);
                const gp_Vec right = q_hat->DN(a_q, k) * std::pow((b_q - a_q) / (1.0 - mu), k);
                const gp_Vec r = occ_r->DN(mu, k);
                const double scale = std::max(left.Magnitude(), right.Magnitude());
                const double gap = std::max((left - right).Magnitude(), (left - r).Magnitude()) / scale;
                derivative_gap = std::max(derivative_gap, gap);
                orders += format("%s%.1e (|R^(%d)| %.3g)", k == 1 ? "" : ", ", gap, k, r.Magnitude());
            }
            // OCCT's own Add with MinM = 0 removes the join knot by itself.
            GeomConvert_CompCurveToBSplineCurve free_join(occ_reparametrized(p_hat, 0.0, mu));
            free_join.Add(occ_reparametrized(q_hat, mu, 1.0), join_tolerance, true, false, 0);
            const Handle(Geom_BSplineCurve) freed = free_join.BSplineCurve();
            const bool knot_removed = freed->NbKnots() == joined->NbKnots() - 1 &&
                                      std::abs(freed->Knot(nearest_knot(freed, mu)) - mu) > 1e-6;
            const double worst = std::max({verdict.jump, derivative_gap});
            const bool pass = added && multiplicity == degree && std::abs(joined->Knot(index) - mu) <= 1e-15 &&
                              verdict.removable && knot_removed && r_has_no_knot_at_mu && worst <= 1e-9 &&
                              joined_gap <= tolerance;
            report.row(pass, "n.merge-join-C3-by-OCCT", worst, 1e-9,
                       format("p_hat on [0, mu] + q_hat on [mu, 1] by CompCurveToBSplineCurve (knot %.6f mult %d): "
                              "RemoveKnot to mult 0 %s (C^3 = C^inf for a cubic), one-sided jumps orders 0-3 %.1e; "
                              "Add(MinM = 0) removes the knot itself: %s; joined vs R %.1e; p_hat/q_hat end "
                              "derivatives scaled to R's parameter vs each other and R's DN(mu), orders 1-3: %s; "
                              "R itself has no knot at mu",
                              joined->Knot(index), multiplicity, verdict.removable ? "ok" : "REFUSED", verdict.jump,
                              knot_removed ? "yes" : "NO", joined_gap, orders.c_str()));
        });
    }

    // d. Our deviation from P-then-Q (reported, and measured by OCCT) beside
    // OCCT's exact join of P and Q, which keeps a C^0 knot.
    if (need_merge("n.merge-deviation-by-OCCT")) {
        guarded(report, "n.merge-deviation-by-OCCT", [&] {
            const double mu = m->report.mu;
            // 2049 samples per curve: every 8th is one of the report's 257.
            double measured = 0.0;
            for (int i = 0; i <= 2048; ++i) {
                const double s = i / 2048.0;
                measured = std::max(measured, occ_r->Value(mu * s).Distance(occ_p->Value(a_p + (b_p - a_p) * s)));
                measured = std::max(measured, occ_r->Value(mu + (1.0 - mu) * s)
                                                  .Distance(occ_q->Value(a_q + (b_q - a_q) * s)));
            }
            const double reported = m->report.max_deviation;
            const double disagreement = std::abs(reported - measured) / std::max(measured, 1e-300);
            report.row(disagreement <= 1e-3 && reported <= measured * (1.0 + 1e-9), "n.merge-deviation-by-OCCT",
                       disagreement, 1e-3,
                       format("R vs P-then-Q at mapped parameters: reported %.6e, OCCT-evaluated %.6e (2049 samples "
                              "per curve) = %.2e of the curves' size %.2g; metric %.3e",
                              reported, measured, measured / size, size, m->report.metric_value));
        });
        guarded(report, "n.merge-vs-OCCT-join", [&] {
            GeomConvert_CompCurveToBSplineCurve join(occ_p);
            const bool added = join.Add(occ_q, 1e-7, true, false, 0);
            const Handle(Geom_BSplineCurve) joined = join.BSplineCurve();
            const int index = nearest_knot(joined, b_p);
            const int multiplicity = joined->Multiplicity(index);
            // How far RemoveKnot can lower the join knot (tolerance 1e-9 size).
            int lowest = multiplicity;
            for (int mult = multiplicity - 1; mult >= 0; --mult) {
                Handle(Geom_BSplineCurve) copy = Handle(Geom_BSplineCurve)::DownCast(joined->Copy());
                if (!copy->RemoveKnot(index, mult, 1e-9 * size)) {
                    break;
                }
                lowest = mult;
            }
            // Its distance to P-then-Q: Q translated to start at P's end (no ratio).
            double distance = 0.0;
            for (int i = 0; i <= 2048; ++i) {
                const double s = i / 2048.0;
                const double u = a_p + (b_p - a_p) * s;
                const double v = a_q + (b_q - a_q) * s;
                distance = std::max(distance, joined->Value(u).Distance(occ_p->Value(u)));
                distance = std::max(distance, joined->Value(b_p + (v - a_q)).Distance(occ_q->Value(v)));
            }
            distance /= size;
            const gp_Vec left = joined->LocalDN(b_p, index - 1, index, 1);
            const gp_Vec right = joined->LocalDN(b_p, index, index + 1, 1);
            const double kink = left.Angle(right) * 180.0 / 3.14159265358979323846;
            const double ours = m->report.max_deviation;
            const bool pass = added && distance <= tolerance && multiplicity == degree && lowest == degree &&
                              r_has_no_knot_at_mu && kink > 1.0;
            report.row(pass, "n.merge-vs-OCCT-join", distance, tolerance,
                       format("OCCT join P + Add(Q, 1e-7, no ratio, MinM 0): exact (distance / size above) but "
                              "knot %.4g keeps mult %d = C^%d (RemoveKnot to %d refused), tangent kink %.2f deg, "
                              "|D1| %.3g vs %.3g; ours: one cubic across mu (no knot there, C^inf), deviation "
                              "%.3e (%.2e of size), %d poles vs OCCT's %d",
                              joined->Knot(index), multiplicity, degree - multiplicity, multiplicity - 1, kink,
                              left.Magnitude(), right.Magnitude(), ours, ours / size, occ_r->NbPoles(),
                              joined->NbPoles()));
        });
    }

    // e. Timing: our merge of the two B-splines (L2 optimal mu, and the
    // paper's discrete mu = 1/2) beside OCCT's join (CompCurveToBSplineCurve).
    if (need_merge("timing.bspline-merge")) {
        guarded(report, "timing.bspline-merge", [&] {
            auto occt_join = [&](int) {
                GeomConvert_CompCurveToBSplineCurve join(occ_p);
                join.Add(occ_q, 1e-7, true, false, 0);
                g_sink = g_sink + static_cast<double>(join.BSplineCurve()->NbPoles());
            };
            const int batches = options.quick ? 1 : 9;
            const Pair optimal = time_pair(
                batches, options.quick ? 1 : 40,
                [&](int) {
                    const bezjoin::Merge again = bezjoin::merge(*p, *q, opts);
                    g_sink = g_sink + again.report.mu;
                },
                options.quick ? 1 : 2000, occt_join);
            timings.push_back({"merge two cubic B-splines (4 spans each)", "bzj_merge L2 optimal mu",
                               "CompCurveToBSplineCurve P+Q (C0)", optimal});
            bezjoin::MergeOptions paper;
            paper.metric = BZJ_METRIC_DISCRETE;
            paper.split = BZJ_SPLIT_HALF;
            paper.fix_ends = true;
            const Pair half = time_pair(
                batches, options.quick ? 1 : 400,
                [&](int) {
                    const bezjoin::Merge again = bezjoin::merge(*p, *q, paper);
                    g_sink = g_sink + again.report.mu;
                },
                options.quick ? 1 : 2000, occt_join);
            timings.push_back({"merge two cubic B-splines (paper setting)", "bzj_merge discrete mu=1/2",
                               "CompCurveToBSplineCurve P+Q (C0)", half});
            report.info("timing.bspline-merge",
                        format("median per call%s: bzj_merge L2 optimal %s, discrete mu=1/2 %s; OCCT "
                               "CompCurveToBSplineCurve join %s (exact, C^0 knot kept)",
                               options.quick ? " [quick: not meaningful]" : "", format_time(optimal.ours_ns).c_str(),
                               format_time(half.ours_ns).c_str(), format_time(optimal.occt_ns).c_str()));
        });
    }

    // f. One OCCT B-spline O on [a, b], split by bzj_curve_split at s (not a
    // knot), merged back with BZJ_SPLIT_GIVEN at mu = (s - a) / (b - a):
    // R(t) = O(a + (b - a) t), derivatives scaled by (b - a)^k.
    const Handle(Geom_BSplineCurve) occ_o = occ_polynomial(
        {gp_Pnt(0.0, 0.0, 0.0), gp_Pnt(0.6, 0.9, 0.2), gp_Pnt(1.5, 1.3, -0.1), gp_Pnt(2.2, 0.6, 0.3),
         gp_Pnt(3.0, -0.2, 0.5), gp_Pnt(3.9, 0.1, 0.2), gp_Pnt(4.5, 1.0, 0.0), gp_Pnt(5.4, 1.2, -0.3),
         gp_Pnt(6.0, 0.5, -0.2)},
        {1.0, 1.6, 2.1, 2.9, 3.3, 4.2}, {4, 1, 1, 2, 1, 4}, degree);
    const double a = occ_o->FirstParameter();
    const double b = occ_o->LastParameter();
    const double s = 2.37;
    const double o_size = pole_size(occ_o);
    guarded(report, "n.merge-split-back", [&] {
        const Curve o = ours_from_occ(occ_o, 3);
        const std::pair<Curve, Curve> halves = o.split(s);
        bezjoin::MergeOptions given;
        given.metric = BZJ_METRIC_L2;
        given.split = BZJ_SPLIT_GIVEN;
        given.mu = (s - a) / (b - a);
        const bezjoin::Merge back = bezjoin::merge(halves.first, halves.second, given);
        // Ours vs OCCT's O, orders 0..3; orders >= 1 not within 1e-9 of a knot
        // (O is only C^1 at its double knot: a side question there).
        std::vector<double> ts;
        for (int i = 0; i <= 2000; ++i) {
            ts.push_back(i / 2000.0);
        }
        const std::vector<double> ours = back.merged.eval_many(ts, 3);
        double scale[4] = {o_size, 0.0, 0.0, 0.0};
        std::vector<std::array<gp_Vec, 4>> theirs(ts.size());
        std::vector<bool> near_knot(ts.size(), false);
        for (std::size_t i = 0; i < ts.size(); ++i) {
            const double u = a + (b - a) * ts[i];
            theirs[i][0] = gp_Vec(occ_o->Value(u).XYZ());
            for (int k = 1; k <= 3; ++k) {
                theirs[i][k] = occ_o->DN(u, k) * std::pow(b - a, k);
                scale[k] = std::max(scale[k], theirs[i][k].Magnitude());
            }
            for (int j = 1; j <= occ_o->NbKnots(); ++j) {
                near_knot[i] = near_knot[i] || std::abs(u - occ_o->Knot(j)) <= 1e-9 * (b - a);
            }
        }
        double error[4] = {0.0, 0.0, 0.0, 0.0};
        for (std::size_t i = 0; i < ts.size(); ++i) {
            for (int k = 0; k <= 3; ++k) {
                if (k > 0 && near_knot[i] && ts[i] != 0.0 && ts[i] != 1.0) {
                    continue;
                }
                const gp_Vec mine = jet_row(std::vector<double>(ours.begin() + 12 * i, ours.begin() + 12 * (i + 1)),
                                            static_cast<std::size_t>(k), 3);
                error[k] = std::max(error[k], (mine - theirs[i][k]).Magnitude() / scale[k]);
            }
        }
        // R's knots are O's mapped to [0, 1] and its poles O's poles.
        const Handle(Geom_BSplineCurve) occ_r_back = occ_bspline(back.merged);
        bool same = occ_r_back->NbKnots() == occ_o->NbKnots() && occ_r_back->NbPoles() == occ_o->NbPoles();
        double knot_gap = 0.0;
        double pole_gap = 0.0;
        for (int i = 1; same && i <= occ_o->NbKnots(); ++i) {
            same = occ_r_back->Multiplicity(i) == occ_o->Multiplicity(i);
            knot_gap = std::max(knot_gap, std::abs(occ_r_back->Knot(i) - (occ_o->Knot(i) - a) / (b - a)));
        }
        for (int i = 1; same && i <= occ_o->NbPoles(); ++i) {
            pole_gap = std::max(pole_gap, occ_r_back->Pole(i).Distance(occ_o->Pole(i)) / o_size);
        }
        const std::pair<double, double> d1 = halves.first.domain();
        const std::pair<double, double> d2 = halves.second.domain();
        const bool pieces = d1.first == a && d1.second == s && d2.first == s && d2.second == b &&
                            halves.first.is_nurbs() && halves.second.is_nurbs() && back.report.mu == given.mu;
        const double worst = std::max({error[0], error[1], error[2], error[3], knot_gap, pole_gap,
                                       back.report.max_deviation / o_size});
        report.row(same && pieces && worst <= tolerance, "n.merge-split-back", worst, tolerance,
                   format("O (%s) split at s = %.2f (not a knot), merged back at mu = %.6f (L2): R vs OCCT's "
                          "O(a + (b - a) t), 2001 t, orders 0-3 (scaled (b - a)^k): %.1e %.1e %.1e %.1e; knots vs "
                          "O's mapped %.1e, poles %.1e; reported deviation %.1e, metric %.1e",
                          describe(occ_o).c_str(), s, given.mu, error[0], error[1], error[2], error[3], knot_gap,
                          pole_gap, back.report.max_deviation, back.report.metric_value));
    });
    // The same through bzj_merge_chain: O cut into three pieces at non-knots
    // (bzj_curve_segment), breakpoints given where they were cut.
    guarded(report, "n.merge_chain-split-back", [&] {
        const Curve o = ours_from_occ(occ_o, 3);
        const double s2 = 3.71;
        std::vector<Curve> parts;
        parts.push_back(o.segment(a, s));
        parts.push_back(o.segment(s, s2));
        parts.push_back(o.segment(s2, b));
        bezjoin::ChainMergeOptions chain_opts;
        chain_opts.metric = BZJ_METRIC_L2;
        chain_opts.split = BZJ_CHAIN_SPLIT_GIVEN;
        chain_opts.breakpoints = {(s - a) / (b - a), (s2 - a) / (b - a)};
        const bezjoin::ChainMerge chain = bezjoin::merge_chain(parts, chain_opts);
        const Handle(Geom_BSplineCurve) occ_chain = occ_bspline(chain.merged);
        double chain_worst = chain.report.max_deviation / o_size;
        for (int i = 0; i <= 2000; ++i) {
            const double t = i / 2000.0;
            chain_worst = std::max(chain_worst, occ_chain->Value(t).Distance(occ_o->Value(a + (b - a) * t)) / o_size);
        }
        bool chain_same = occ_chain->NbKnots() == occ_o->NbKnots() && chain.pieces.size() == 3 &&
                          chain.breakpoints.size() == 4;
        for (int i = 1; chain_same && i <= occ_o->NbKnots(); ++i) {
            chain_same = occ_chain->Multiplicity(i) == occ_o->Multiplicity(i);
            chain_worst = std::max(chain_worst, std::abs(occ_chain->Knot(i) - (occ_o->Knot(i) - a) / (b - a)));
        }
        for (std::size_t j = 0; chain_same && j < chain.pieces.size(); ++j) {
            chain_same = chain.pieces[j].domain() == parts[j].domain();
        }
        report.row(chain_same && chain_worst <= tolerance, "n.merge_chain-split-back", chain_worst, tolerance,
                   format("O cut at %.2f and %.2f (not knots) by bzj_curve_segment, merge_chain L2 at the mapped "
                          "breakpoints %.6f, %.6f: OCCT's evaluation of R vs O (2001 t), R's knots vs O's mapped, "
                          "pieces on the parts' domains; reported deviation %.1e",
                          s, s2, chain_opts.breakpoints[0], chain_opts.breakpoints[1], chain.report.max_deviation));
    });
}

// status_name() and last_error(), the two functions bezjoin::Error reads.
void check_status_and_message(Report& report) {
    guarded(report, "g.status_name+last_error", [&] {
        bool pass = bezjoin::status_name(BZJ_ERR_SINGULAR) == "BZJ_ERR_SINGULAR" &&
                    bezjoin::status_name(12345) == "BZJ_UNKNOWN_STATUS";
        std::string during;
        std::string what;
        const Curve c(2, 1, {0.0, 0.0, 1.0, 1.0});
        try {
            (void)c.split(1.5);
        } catch (const bezjoin::Error& e) {
            during = bezjoin::last_error();
            what = e.what();
        }
        pass = pass && !during.empty() && during.find("1.5") != std::string::npos &&
               what.find(during) != std::string::npos;
        (void)c.degree();  // a success clears the message
        pass = pass && bezjoin::last_error().empty();
        report.row(pass, "g.status_name+last_error", pass ? 0.0 : 1.0, 0.0, during);
    });
}

void write_step(Report& report, StepScene& scene, std::mt19937_64& rng, const Options& options) {
    guarded(report, "step.write-and-read-back", [&] {
        // Plus a few plain curves of ours, degrees 2..5, in a row.
        for (std::size_t degree = 2; degree <= 5; ++degree) {
            const Curve c(3, degree, random_points(rng, 3, degree));
            scene.add(c, gp_Vec(3.0 * static_cast<double>(degree), -4.0, 0.0));
        }
        STEPControl_Writer writer;
        Interface_Static::SetCVal("write.step.schema", "AP214IS");
        if (writer.Transfer(scene.compound, STEPControl_AsIs) != IFSelect_RetDone ||
            writer.Write(options.step_path.c_str()) != IFSelect_RetDone) {
            throw std::runtime_error("STEPControl_Writer failed for " + options.step_path);
        }
        STEPControl_Reader reader;
        if (reader.ReadFile(options.step_path.c_str()) != IFSelect_RetDone) {
            throw std::runtime_error("STEPControl_Reader cannot read " + options.step_path);
        }
        reader.TransferRoots();
        int edges = 0;
        for (TopExp_Explorer it(reader.OneShape(), TopAbs_EDGE); it.More(); it.Next()) {
            ++edges;
        }
        const bool pass = edges == scene.edges;
        // How many edges the file holds, for FreeCAD's own reading of it
        // (freecad/tests/test_step_in_freecad.py).
        std::ofstream(options.step_path + ".edges") << scene.edges << "\n";
        report.row(pass, "step.write-and-read-back", std::abs(edges - scene.edges), 0.0,
                   format("%s: %d edges written, %d read back", options.step_path.c_str(), scene.edges,
                          edges));
    });
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) {
            options.quick = true;
        } else if (std::strcmp(argv[i], "--step") == 0 && i + 1 < argc) {
            options.step_path = argv[++i];
        } else if (std::strcmp(argv[i], "--leak-on-purpose") == 0) {
            Curve leaked(2, 1, {0.0, 0.0, 1.0, 1.0});
            std::printf("leaking one curve handle on purpose: %p\n", static_cast<void*>(leaked.release()));
            return 0;
        } else {
            std::fprintf(stderr, "usage: %s [--quick] [--step FILE] [--leak-on-purpose]\n", argv[0]);
            return 2;
        }
    }
    // OCCT's STEP writer prints to stdout through the default messenger.
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));

    std::printf("bezjoin %s vs OpenCASCADE %s%s\n", bezjoin::version().c_str(), OCC_VERSION_COMPLETE,
                options.quick ? " (quick: timings not meaningful)" : "");
    Report report;
    StepScene scene;
    std::vector<Timing> timings;
    std::mt19937_64 rng(20261122);

    check_values_and_derivatives(report, rng);
    check_exact_operations(report, rng);
    check_error_path(report);
    check_connect(report, scene, timings, options);
    check_nurbs(report);
    std::mt19937_64 nurbs_rng(16);  // its own stream: the checks after it see the same numbers as before
    check_nurbs_dn_and_segment(report, nurbs_rng, timings, options);
    check_ellipse(report, options);
    check_nurbs_fillets(report, timings, options);
    check_fillet(report, scene, timings, options);
    check_fillet_radius(report, timings, options);
    check_radius_wire(report);
    check_merge(report, scene, timings, options);
    check_lagrange(report, scene);
    check_auto_scale(report);
    check_intersect_detailed(report);
    check_fillet_deviation(report);
    check_fillet_chain(report, scene);
    check_lagrange_degree(report);
    check_merge_degree_and_chain(report);
    check_bspline_merge(report, timings, options);
    check_status_and_message(report);
    time_evaluation(report, timings, options);
    write_step(report, scene, rng, options);

    std::printf("\nSide by side (median per call; ratio = median over alternating batches of OCCT time / our time)%s\n",
                options.quick ? " [quick run: not meaningful]" : "");
    for (const Timing& t : timings) {
        // A ratio below 0.1 with three decimals (one would print 0.0x).
        std::printf("TIME %-44s ours %10s (%s)  OCCT %10s (%s)  ratio %8.*fx\n", t.name.c_str(),
                    format_time(t.pair.ours_ns).c_str(), t.ours_label.c_str(),
                    format_time(t.pair.occt_ns).c_str(), t.occt_label.c_str(), t.pair.ratio < 0.095 ? 3 : 1,
                    t.pair.ratio);
    }
    std::printf("\n%s: %d failure(s)\n", report.failures == 0 ? "ALL PASS" : "FAILED", report.failures);
    return report.failures == 0 ? 0 : 1;
}

// C++ consumer of an installed bezjoin (find_package(bezjoin CONFIG) +
// bezjoin::bezjoin). Checks values against hand computation:
//   quadratic in 3-D, P0=(0,0,0) P1=(1,2,0) P2=(2,0,4):
//     P(t)  = (1-t)^2 P0 + 2t(1-t) P1 + t^2 P2;  P(1/4) = (1/2, 3/4, 1/4)
//     P'(t) = 2(1-t)(P1-P0) + 2t(P2-P1);         P'(1/4) = (2, 2, 2)
//   elevating to degree 3 keeps every point (checked at t = 1/4);
//   segment(0.25, 0.75) starts at P(1/4);
//   split at t = 1.5 is refused with BZJ_ERR_INVALID_ARGUMENT naming t.
#include <bezjoin.h>
#if __has_include(<bezjoin.hpp>)
#include <bezjoin.hpp>  // installed when the repo has the C++ wrapper: must compile here
#endif

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

namespace {
int failures = 0;

struct CurveDeleter {
    void operator()(BzjCurve* c) const { bzj_curve_free(c); }
};
using Curve = std::unique_ptr<BzjCurve, CurveDeleter>;

void check(bool ok, const std::string& what) {
    if (!ok) {
        std::fprintf(stderr, "FAIL %s (last error: %s)\n", what.c_str(), bzj_last_error());
        ++failures;
    }
}

bool close(double a, double b) { return std::fabs(a - b) <= 1e-14 * (1.0 + std::fabs(b)); }
}  // namespace

int main() {
    const double pts[] = {0, 0, 0, 1, 2, 0, 2, 0, 4};
    BzjCurve* raw = nullptr;
    check(bzj_curve_new(3, 2, pts, 9, &raw) == BZJ_OK && raw != nullptr, "curve_new");
    Curve c(raw);
    if (!c) return 1;

    double d[6];
    check(bzj_curve_eval(c.get(), 0.25, 1, d, 6) == BZJ_OK, "eval");
    const double want[6] = {0.5, 0.75, 0.25, 2.0, 2.0, 2.0};
    for (int i = 0; i < 6; ++i) check(close(d[i], want[i]), "eval value " + std::to_string(i));

    BzjCurve* e = nullptr;
    check(bzj_curve_elevate(c.get(), 3, &e) == BZJ_OK, "elevate");
    Curve elevated(e);
    size_t degree = 0;
    check(bzj_curve_degree(elevated.get(), &degree) == BZJ_OK && degree == 3, "elevated degree");
    double v[3];
    check(bzj_curve_eval(elevated.get(), 0.25, 0, v, 3) == BZJ_OK, "eval elevated");
    for (int i = 0; i < 3; ++i) check(close(v[i], want[i]), "elevated value " + std::to_string(i));

    BzjCurve* s = nullptr;
    check(bzj_curve_segment(c.get(), 0.25, 0.75, &s) == BZJ_OK, "segment");
    Curve segment(s);
    double sp[9];
    check(bzj_curve_points(segment.get(), sp, 9) == BZJ_OK, "segment points");
    for (int i = 0; i < 3; ++i) check(close(sp[i], want[i]), "segment start " + std::to_string(i));

    BzjCurve* left = reinterpret_cast<BzjCurve*>(&failures);
    BzjCurve* right = reinterpret_cast<BzjCurve*>(&failures);
    check(bzj_curve_split(c.get(), 1.5, &left, &right) == BZJ_ERR_INVALID_ARGUMENT, "split status");
    check(left == nullptr && right == nullptr, "handles cleared on error");
    check(std::strstr(bzj_last_error(), "t") != nullptr && std::strstr(bzj_last_error(), "1.5") != nullptr,
          std::string("message names t = 1.5: ") + bzj_last_error());

    if (failures != 0) {
        std::fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    std::printf("C++ CMake consumer: bezjoin %s OK\n", bzj_version());
    return 0;
}

// The floor of the demo's connect row (issue 20): the connect C3/C4 of a cubic
// and a quartic in 3D with scales 1, written out for that one case and
// nothing else. The two jets are the de Casteljau pyramids spelled out, the
// two triangular substitutions and one residual per condition row have
// constant bounds, and the result goes into a handle-like pair of heap
// blocks, as bzj_connect's does. It checks nothing that bzj_connect checks
// (no rounding bounds, no data scale, no argument validation), so it is not
// an alternative: it measures what any connect of this case must at least
// cost on the machine, next to bzj_connect and OCCT's route.
//
// Compiled with -O3 -funroll-loops (CMakeLists.txt): the floor should be as
// low as the compiler can make it.
#include "connect_floor.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace {

// P(t), P'(t), P''(t), P'''(t) of a cubic, coordinates interleaved (x y z).
inline void cubic_jet(const double* pts, double t, double (*out)[3]) {
    const double s = 1.0 - t;
    for (int c = 0; c < 3; ++c) {
        const double a0 = pts[c], a1 = pts[3 + c], a2 = pts[6 + c], a3 = pts[9 + c];
        const double b0 = s * a0 + t * a1, b1 = s * a1 + t * a2, b2 = s * a2 + t * a3;
        const double c0 = s * b0 + t * b1, c1 = s * b1 + t * b2;
        out[0][c] = s * c0 + t * c1;
        out[1][c] = 3.0 * (c1 - c0);
        out[2][c] = 6.0 * (b2 - 2.0 * b1 + b0);
        out[3][c] = 6.0 * (a3 - 3.0 * a2 + 3.0 * a1 - a0);
    }
}

// Q(t) .. Q''''(t) of a quartic.
inline void quartic_jet(const double* pts, double t, double (*out)[3]) {
    const double s = 1.0 - t;
    for (int c = 0; c < 3; ++c) {
        const double a0 = pts[c], a1 = pts[3 + c], a2 = pts[6 + c], a3 = pts[9 + c], a4 = pts[12 + c];
        const double b0 = s * a0 + t * a1, b1 = s * a1 + t * a2, b2 = s * a2 + t * a3,
                     b3 = s * a3 + t * a4;
        const double c0 = s * b0 + t * b1, c1 = s * b1 + t * b2, c2 = s * b2 + t * b3;
        const double d0 = s * c0 + t * c1, d1 = s * c1 + t * c2;
        out[0][c] = s * d0 + t * d1;
        out[1][c] = 4.0 * (d1 - d0);
        out[2][c] = 12.0 * (c2 - 2.0 * c1 + c0);
        out[3][c] = 24.0 * (b3 - 3.0 * b2 + 3.0 * b1 - b0);
        out[4][c] = 24.0 * (a4 - 4.0 * a3 + 6.0 * a2 - 4.0 * a1 + a0);
    }
}

constexpr int kP = 3;            // C^3 at P
constexpr int kQ = 4;            // C^4 at Q
constexpr int kN = kP + kQ + 1;  // degree of R

constexpr double kBinomial[5][5] = {
    {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};

// n!/(n-k)! for n = 8 and its reciprocal.
struct Falling {
    double value[kN + 1];
    double inverse[kN + 1];
    constexpr Falling() : value(), inverse() {
        double f = 1.0;
        for (int k = 0; k <= kN; ++k) {
            value[k] = f;
            inverse[k] = 1.0 / f;
            f *= kN - k;
        }
    }
};
constexpr Falling kFalling;

inline double sign(int k) { return (k & 1) ? -1.0 : 1.0; }

}  // namespace

ConnectFloor* connect_floor(const double* p, double u0, const double* q, double v0) {
    double tp[kP + 1][3];
    double tq[kQ + 1][3];
    cubic_jet(p, u0, tp);
    quartic_jet(q, v0, tq);
    double r[kN + 1][3];
    // P end: R^(k)(0) = n!/(n-k)! sum_j (-1)^(k-j) C(k,j) R_j = P^(k)(u0).
    for (int k = 0; k <= kP; ++k) {
        for (int c = 0; c < 3; ++c) {
            double x = tp[k][c] * kFalling.inverse[k];
            for (int j = 0; j < k; ++j) {
                x -= sign(k - j) * kBinomial[k][j] * r[j][c];
            }
            r[k][c] = x;
        }
    }
    // Q end: R^(k)(1) = n!/(n-k)! sum_j (-1)^j C(k,j) R_(n-j) = Q^(k)(v0).
    for (int k = 0; k <= kQ; ++k) {
        for (int c = 0; c < 3; ++c) {
            double x = tq[k][c] * kFalling.inverse[k];
            for (int j = 0; j < k; ++j) {
                x -= sign(j) * kBinomial[k][j] * r[kN - j][c];
            }
            r[kN - k][c] = sign(k) * x;
        }
    }
    // One residual per condition row, from R's points (squares only; one
    // square root at the end).
    double worst_difference = 0.0;
    double worst_target = 1.0;
    for (int k = 0; k <= kP; ++k) {
        double difference = 0.0;
        double target = 0.0;
        for (int c = 0; c < 3; ++c) {
            double sum = 0.0;
            for (int j = 0; j <= k; ++j) {
                sum += sign(k - j) * kBinomial[k][j] * r[j][c];
            }
            const double d = kFalling.value[k] * sum - tp[k][c];
            difference += d * d;
            target += tp[k][c] * tp[k][c];
        }
        worst_difference = difference > worst_difference ? difference : worst_difference;
        worst_target = target > worst_target ? target : worst_target;
    }
    for (int k = 0; k <= kQ; ++k) {
        double difference = 0.0;
        double target = 0.0;
        for (int c = 0; c < 3; ++c) {
            double sum = 0.0;
            for (int j = 0; j <= k; ++j) {
                sum += sign(j) * kBinomial[k][j] * r[kN - j][c];
            }
            const double d = kFalling.value[k] * sum - tq[k][c];
            difference += d * d;
            target += tq[k][c] * tq[k][c];
        }
        worst_difference = difference > worst_difference ? difference : worst_difference;
        worst_target = target > worst_target ? target : worst_target;
    }
    auto* out = static_cast<ConnectFloor*>(std::malloc(sizeof(ConnectFloor)));
    if (out == nullptr) {
        return nullptr;
    }
    out->points = static_cast<double*>(std::malloc(sizeof r));
    if (out->points == nullptr) {
        std::free(out);
        return nullptr;
    }
    std::memcpy(out->points, r, sizeof r);
    out->count = kN + 1;
    out->residual = std::sqrt(worst_difference / worst_target);
    return out;
}

void connect_floor_free(ConnectFloor* floor) {
    if (floor != nullptr) {
        std::free(floor->points);
        std::free(floor);
    }
}

// The floor of the demo's connect row (connect_floor.cpp): an unchecked
// connect C3/C4 of a cubic P and a quartic Q in 3D, scales 1, written out
// for that case only. A measurement aid, not an API.
#pragma once

#include <cstddef>

struct ConnectFloor {
    double* points;   // R's 9 control points, row-major (x y z)
    std::size_t count;
    double residual;  // largest relative residual of the 9 condition rows
};

// P: 4 control points, Q: 5, row-major 3D. NULL only when malloc fails.
ConnectFloor* connect_floor(const double* p, double u0, const double* q, double v0);
void connect_floor_free(ConnectFloor* floor);

//! Splines and curves: piecewise polynomials, cubic/Hermite/PCHIP/Akima, Catmull-Rom, Bezier,
//! B-spline, NURBS, arc length and orientation interpolation.

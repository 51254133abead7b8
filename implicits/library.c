/* implicits/library.c -- the built-in library (see library.h). The Hijazi seed's Table 1 garbles some
 * constants; each choice made here is noted next to its entry and in docs/language.md. */
#include "library.h"
#include <string.h>

#define ROTATE_PRELUDE                                                                                        \
    "n = sqrt(ax^2 + ay^2 + az^2); kx = ax / n; ky = ay / n; kz = az / n\n"                                    \
    "c = cos(angle); s = sin(angle); d = (kx*x + ky*y + kz*z) * (1 - c)\n"

const lib_entry lib_entries[] = {
    /* ---- Table 1 of the Hijazi seed */
    {"sphere", LIB_PRIMITIVE, "sphere(r = 1)", "", {"x^2 + y^2 + z^2 - r^2"}},
    /* The seed's pseudo-cube is x^500 + y^500 + z^500 - r^2: n must be an even integer. */
    {"pseudocube", LIB_PRIMITIVE, "pseudocube(r = 1, n = 500)", "", {"x^n + y^n + z^n - r^2"}},
    {"cylinder", LIB_PRIMITIVE, "cylinder(r = 1)", "", {"x^2 + y^2 - r^2"}},
    /* The seed prints "z^2125": read as z^2 - 0.125, so the tube radius is sqrt(0.125). */
    {"torus", LIB_PRIMITIVE, "torus(R = 1, r = sqrt(0.125))", "", {"(R - sqrt(x^2 + y^2))^2 + z^2 - r^2"}},
    {"bretzel4", LIB_PRIMITIVE, "bretzel4()", "",
     {"0.1 * (x^2 * (1.21 - x^2)^2 * (3.8 - x^2)^3 - 10 * y^2)^2 + 60 * z^2 - 2"}},
    /* The seed prints "x^4 - rx^2": read as x^4 - 5x^2, like the y and z terms. */
    {"tangle", LIB_PRIMITIVE, "tangle()", "", {"x^4 - 5*x^2 + y^4 - 5*y^2 + z^4 - 5*z^2 + 11.8"}},
    {"decocube", LIB_PRIMITIVE, "decocube()", "",
     {"((x^2 + y^2 - 0.8^2)^2 + (z^2 - 1)^2) * ((y^2 + z^2 - 0.8^2)^2 + (x^2 - 1)^2)"
      " * ((z^2 + x^2 - 0.8^2)^2 + (y^2 - 1)^2) - 0.02"}},
    {"superquadric", LIB_PRIMITIVE, "superquadric()", "", {"x^200 + (0.5 * y^4 + 0.5 * z^4)^4 - 1"}},
    {"ellipsoid", LIB_PRIMITIVE, "ellipsoid(a = 2, b = 2, c = 1)", "", {"(x / a)^2 + (y / b)^2 + (z / c)^2 - 1"}},
    {"heart", LIB_PRIMITIVE, "heart()", "", {"(2 * x^2 + y^2 + z^2 - 1)^3 - (0.1 * x^2 + y^2) * z^3"}},
    /* The seed prints "4y^3(15y)^3": read as 4 y^3 (1 - y)^3, Hauser's citrus (a lemon between y = 0 and 1). */
    {"citrus", LIB_PRIMITIVE, "citrus()", "", {"x^2 + z^2 - 4 * y^3 * (1 - y)^3"}},
    /* The seed prints "sin(z)^3125": read as sin(z)^3 - 0.125, by the same rule as the torus. Unbounded in z. */
    {"trigtorus", LIB_PRIMITIVE, "trigtorus()", "", {"(1 - sqrt(x^2 + y^2))^2 + sin(z)^3 - 0.125"}},
    /* ---- more primitives */
    {"box", LIB_PRIMITIVE, "box(a = 1, b = a, c = b)", "", {"max(abs(x) - a, abs(y) - b, abs(z) - c)"}},
    {"plane", LIB_PRIMITIVE, "plane(nx = 0, ny = 0, nz = 1, d = 0)", "", {"nx*x + ny*y + nz*z - d"}},
    {"halfspace", LIB_PRIMITIVE, "halfspace(nx = 0, ny = 0, nz = 1, d = 0)", "", {"nx*x + ny*y + nz*z - d"}},
    {"cone", LIB_PRIMITIVE, "cone(r = 1, h = 2)", "", {"max(sqrt(x^2 + y^2) - r * (h - z) / h, -z, z - h)"}},
    {"capsule", LIB_PRIMITIVE, "capsule(r = 0.5, h = 1)", "", {"x^2 + y^2 + max(abs(z) - h, 0)^2 - r^2"}},
    {"capped_cylinder", LIB_PRIMITIVE, "capped_cylinder(r = 1, h = 1)", "", {"max(x^2 + y^2 - r^2, z^2 - h^2)"}},
    {"gyroid", LIB_PRIMITIVE, "gyroid(k = 1)", "",
     {"sin(k*x) * cos(k*y) + sin(k*y) * cos(k*z) + sin(k*z) * cos(k*x)"}},
    /* ---- blends */
    {"smooth_union", LIB_BLEND, "smooth_union(a, b, r = 0.25)", "",
     {"min(a, b) - max(r - abs(a - b), 0)^2 / (4 * r)"}},
    {"smooth_intersection", LIB_BLEND, "smooth_intersection(a, b, r = 0.25)", "",
     {"max(a, b) + max(r - abs(a - b), 0)^2 / (4 * r)"}},
    {"smooth_difference", LIB_BLEND, "smooth_difference(a, b, r = 0.25)", "",
     {"max(a, -b) + max(r - abs(a + b), 0)^2 / (4 * r)"}},
    {"product", LIB_BLEND, "product(a, b, k = 0)", "", {"a * b - k"}},
    {"morph", LIB_BLEND, "morph(a, b, s = t)", "", {"(1 - s) * a + s * b"}},
    /* Written as a weighted mean, not a + (b - a) w: where a and b are both positive the enclosure stays
     * positive, so bounds are provable. */
    {"sigmoid_blend", LIB_BLEND, "sigmoid_blend(a, b, s = t, k = 12, c = 0.5)", "w = 1 / (1 + exp(-k * (s - c)))",
     {"(1 - w) * a + w * b"}},
    {"pown", LIB_BLEND, "pown(a, n)", "", {"a^n"}},
    /* ---- transforms: a point p is in the moved solid when the inverse motion takes it into the original */
    {"move", LIB_TRANSFORM, "move(shape, dx = 0, dy = 0, dz = 0)", "", {"x - dx", "y - dy", "z - dz"}},
    {"translate", LIB_TRANSFORM, "translate(shape, dx = 0, dy = 0, dz = 0)", "", {"x - dx", "y - dy", "z - dz"}},
    {"scale", LIB_TRANSFORM, "scale(shape, sx = 1, sy = sx, sz = sy)", "", {"x / sx", "y / sy", "z / sz"}},
    {"rotatex", LIB_TRANSFORM, "rotatex(shape, angle)", "",
     {"x", "cos(angle) * y + sin(angle) * z", "cos(angle) * z - sin(angle) * y"}},
    {"rotatey", LIB_TRANSFORM, "rotatey(shape, angle)", "",
     {"cos(angle) * x - sin(angle) * z", "y", "sin(angle) * x + cos(angle) * z"}},
    {"rotatez", LIB_TRANSFORM, "rotatez(shape, angle)", "",
     {"cos(angle) * x + sin(angle) * y", "cos(angle) * y - sin(angle) * x", "z"}},
    /* Rodrigues' formula for the rotation by -angle about the unit axis k. */
    {"rotate", LIB_TRANSFORM, "rotate(shape, angle, ax = 0, ay = 0, az = 1)", ROTATE_PRELUDE,
     {"x*c - (ky*z - kz*y)*s + kx*d", "y*c - (kz*x - kx*z)*s + ky*d", "z*c - (kx*y - ky*x)*s + kz*d"}},
};
const int lib_count = (int)(sizeof lib_entries / sizeof lib_entries[0]);

const lib_entry *lib_find(const char *name) {
    for (int i = 0; i < lib_count; i++)
        if (strcmp(lib_entries[i].name, name) == 0)
            return &lib_entries[i];
    return NULL;
}

// SPDX-License-Identifier: Apache-2.0
// Ray queries. Rays and hits cross as raw bytes laid out exactly as ppm_ray and ppm_hit; the
// Python side views them through numpy structured dtypes built from the layouts exported
// here (ray_layout / hit_layout), so field offsets come from the compiler, not from a copy.
#include "arrays.h"
#include "objects.h"

#include <cstddef>

namespace nb = nanobind;

namespace ppm_py {

namespace {

// A dict[str, Any] in the generated stubs.
using LayoutDict = nb::typed<nb::dict, nb::str, nb::any>;

// (names, formats, offsets, itemsize): the arguments of numpy.dtype for a C struct.
struct Layout {
    nb::list names, formats, offsets;
    void add(const char *name, const char *format, size_t offset) {
        names.append(name);
        formats.append(format);
        offsets.append(offset);
    }
    LayoutDict dict(size_t itemsize) const {
        nb::dict d;
        d["names"] = names;
        d["formats"] = formats;
        d["offsets"] = offsets;
        d["itemsize"] = itemsize;
        return d;
    }
};

LayoutDict ray_layout() {
    Layout l;
    l.add("org", "(3,)f8", offsetof(ppm_ray, org));
    l.add("tnear", "f8", offsetof(ppm_ray, tnear));
    l.add("dir", "(3,)f8", offsetof(ppm_ray, dir));
    l.add("tfar", "f8", offsetof(ppm_ray, tfar));
    return l.dict(sizeof(ppm_ray));
}

LayoutDict hit_layout() {
    Layout l;
    l.add("t", "f8", offsetof(ppm_hit, t));
    l.add("u", "f8", offsetof(ppm_hit, u));
    l.add("v", "f8", offsetof(ppm_hit, v));
    l.add("p", "(3,)f8", offsetof(ppm_hit, p));
    l.add("p_error", "f8", offsetof(ppm_hit, p_error));
    l.add("ng", "(3,)f8", offsetof(ppm_hit, ng));
    l.add("ns", "(3,)f8", offsetof(ppm_hit, ns));
    l.add("geom_id", "u4", offsetof(ppm_hit, geom_id));
    l.add("prim_id", "u4", offsetof(ppm_hit, prim_id));
    l.add("material", "u4", offsetof(ppm_hit, material));
    l.add("reserved", "u4", offsetof(ppm_hit, reserved));
    return l.dict(sizeof(ppm_hit));
}

// The rays of a byte buffer; numpy allocations are aligned for doubles.
size_t ray_count(const Bytes &rays) { return groups_of(rays, sizeof(ppm_ray), "rays"); }

} // namespace

void bind_queries(nb::module_ &m, nb::class_<Scene> &cls) {
    m.def("ray_layout", &ray_layout);
    m.def("hit_layout", &hit_layout);
    // Large batches run on the context's worker threads; without the GIL other Python threads
    // go on meanwhile.
    cls.def("intersect", [](Scene &s, const Bytes &rays, OutBytes hits) {
        const size_t count = ray_count(rays);
        if (hits.size() != count * sizeof(ppm_hit)) throw nb::value_error("hits: need one ppm_hit per ray");
        auto scene = s.borrow();
        nb::gil_scoped_release unlocked;
        check(ppm_scene_intersect(scene.get(), reinterpret_cast<const ppm_ray *>(rays.data()), count,
                                  reinterpret_cast<ppm_hit *>(hits.data())));
    });
    cls.def("occluded", [](Scene &s, const Bytes &rays, OutBytes occluded) {
        const size_t count = ray_count(rays);
        if (occluded.size() != count) throw nb::value_error("occluded: need one byte per ray");
        auto scene = s.borrow();
        nb::gil_scoped_release unlocked;
        check(ppm_scene_occluded(scene.get(), reinterpret_cast<const ppm_ray *>(rays.data()), count, occluded.data()));
    });
}

} // namespace ppm_py

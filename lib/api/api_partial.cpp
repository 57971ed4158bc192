// SPDX-License-Identifier: Apache-2.0
// The C API of partial renders (ppm.h, "Partial renders").
#include "api/api_renderer.h"
#include "api/api_support.h"
#include "film/partial.h"

#include <cstring>

namespace {

using namespace ppm::api;

// The handle is the Partial itself: ppm_partial_t is never defined, only converted to and from.
ppm_partial to_handle(ppm::Partial *partial) { return reinterpret_cast<ppm_partial>(partial); }
ppm::Partial &from_handle(ppm_partial partial) { return *reinterpret_cast<ppm::Partial *>(partial); }

template <class Body> ppm_status partial_call(ppm_partial partial, Body &&body) noexcept {
    if (!partial) return guarded(nullptr, [] { ppm::invalid_argument("partial is NULL"); });
    return guarded(nullptr, [&] { body(from_handle(partial)); });
}

template <class Make> ppm_status make_partial(ppm_partial *out_partial, Make &&make) noexcept {
    return guarded(nullptr, [&] {
        require(out_partial, "out_partial");
        *out_partial = nullptr;
        *out_partial = to_handle(make());
    });
}

} // namespace

extern "C" {

ppm_status ppm_renderer_render_pass_index(ppm_renderer renderer, uint64_t pass_index) {
    return renderer_call(renderer, [&](ppm::Renderer &r) { r.render_pass_index(pass_index); });
}

// The first name of ppm_renderer_render_pass_index, exported for the programs that call it.
ppm_status ppm_render_pass_index(ppm_renderer renderer, uint64_t pass_index) {
    return ppm_renderer_render_pass_index(renderer, pass_index);
}

ppm_status ppm_renderer_get_partial(ppm_renderer renderer, ppm_partial *out_partial) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        require(out_partial, "out_partial");
        *out_partial = nullptr;
        *out_partial = to_handle(r.make_partial());
    });
}

ppm_status ppm_renderer_save_partial(ppm_renderer renderer, const char *path) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        require(path, "path");
        ppm::Owned<ppm::Partial>(r.make_partial())->save(path);
    });
}

ppm_status ppm_renderer_merge_partial(ppm_renderer renderer, ppm_partial partial) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        require(partial, "partial");
        r.merge_partial(from_handle(partial));
    });
}

ppm_status ppm_partial_load(const char *path, ppm_partial *out_partial) {
    return make_partial(out_partial, [&] {
        require(path, "path");
        return ppm::Partial::load(path);
    });
}

ppm_status ppm_partial_load_memory(const void *data, size_t size, ppm_partial *out_partial) {
    return make_partial(out_partial, [&] {
        if (size > 0) require(data, "data");
        return ppm::Partial::parse(static_cast<const char *>(data), size, "a partial render in memory");
    });
}

ppm_status ppm_partial_save(ppm_partial partial, const char *path) {
    return partial_call(partial, [&](ppm::Partial &p) {
        require(path, "path");
        p.save(path);
    });
}

ppm_status ppm_partial_serialize(ppm_partial partial, const void **out_data, size_t *out_size) {
    return partial_call(partial, [&](ppm::Partial &p) {
        require(out_data, "out_data");
        require(out_size, "out_size");
        const std::vector<char> &bytes = p.serialized();
        *out_data = bytes.data();
        *out_size = bytes.size();
    });
}

ppm_status ppm_partial_merge(ppm_partial into, ppm_partial from) {
    return partial_call(into, [&](ppm::Partial &p) {
        require(from, "from");
        if (from == into) ppm::invalid_argument("a partial cannot be merged with itself");
        p.merge(from_handle(from));
    });
}

ppm_status ppm_partial_retain(ppm_partial partial) {
    return partial_call(partial, [](ppm::Partial &p) { p.retain(); });
}

void ppm_partial_release(ppm_partial partial) {
    if (partial) from_handle(partial).release();
}

ppm_status ppm_partial_get_int(ppm_partial partial, const char *key, int64_t *out_value) {
    return partial_call(partial, [&](ppm::Partial &p) {
        require_key(key);
        require(out_value, "out_value");
        const std::string k = key;
        const ppm::PassSums &sums = p.sums();
        if (k == "width")
            *out_value = p.identity().width;
        else if (k == "height")
            *out_value = p.identity().height;
        else if (k == "passes")
            *out_value = static_cast<int64_t>(sums.passes().count());
        else if (k == "pass_total")
            *out_value = static_cast<int64_t>(p.pass_total());
        else if (k == "photons_emitted")
            *out_value = static_cast<int64_t>(sums.photons_emitted());
        else if (k == "pass_ranges")
            *out_value = static_cast<int64_t>(sums.passes().ranges().size());
        else if (k == "rejected")
            *out_value = static_cast<int64_t>(sums.rejected());
        else
            ppm::invalid_argument(
                "unknown integer partial key '" + k +
                "' (keys: width, height, passes, pass_total, photons_emitted, pass_ranges, rejected)");
    });
}

ppm_status ppm_partial_set_int(ppm_partial partial, const char *key, int64_t value) {
    return partial_call(partial, [&](ppm::Partial &p) {
        require_key(key);
        if (std::string(key) != "pass_total")
            ppm::invalid_argument("partial key '" + std::string(key) + "' cannot be set (settable: pass_total)");
        if (value < 0 || static_cast<uint64_t>(value) > ppm::kPassIndexLimit)
            ppm::invalid_argument("pass_total must be in 0 .. 2^32, not " + std::to_string(value));
        p.set_pass_total(static_cast<uint64_t>(value));
    });
}

ppm_status ppm_partial_get_passes(ppm_partial partial, uint64_t *out, size_t capacity, size_t *out_count) {
    return partial_call(partial, [&](ppm::Partial &p) {
        require(out_count, "out_count");
        const auto &ranges = p.sums().passes().ranges();
        *out_count = ranges.size();
        if (capacity == 0 && !out) return;
        require(out, "out");
        if (capacity < 2 * ranges.size())
            ppm::invalid_argument("the partial holds " + std::to_string(ranges.size()) + " ranges, " +
                                  std::to_string(2 * ranges.size()) + " numbers; out holds " +
                                  std::to_string(capacity));
        for (size_t i = 0; i < ranges.size(); ++i) out[2 * i] = ranges[i].first, out[2 * i + 1] = ranges[i].end;
    });
}

ppm_status ppm_partial_get_layer(ppm_partial partial, const char *layer, float *out, size_t count) {
    return partial_call(partial, [&](ppm::Partial &p) {
        require(layer, "layer");
        const size_t needed =
            static_cast<size_t>(p.identity().width) * p.identity().height * ppm::Film::layer_channels(layer);
        require(out, "out");
        if (count < needed)
            ppm::invalid_argument("layer '" + std::string(layer) + "' needs " + std::to_string(needed) +
                                  " floats, out holds " + std::to_string(count));
        p.read_layer(layer, out);
    });
}

} // extern "C"

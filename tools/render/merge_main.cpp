// SPDX-License-Identifier: Apache-2.0
// ppm-merge: merges the partial renders of one render (ppm-render --pass-range ... --partial)
// into its image, exactly: the merge of passes 0..N-1 is the image one process rendering N
// passes would give, bit for bit, whatever the split and order.
#include <ppm/ppm.h>

#include "common/command_line.h"
#include "common/handle.h"
#include "common/status.h"
#include "image_writer.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace ppm_render;

namespace {

const char *const description =
    "Merges partial renders (ppm-render --pass-range A:B --partial PATH) of one render into\n"
    "its image. Partials of another scene, camera or settings, or with a pass in common, are\n"
    "refused. Merging an incomplete set writes the image of the passes present (their mean)\n"
    "and names the missing ones.";
const char *const footer = "Exit status: 0 done, 1 usage error, 2 runtime error (a bad, foreign or overlapping\n"
                           "partial, an unwritable image, missing passes with --require-complete).";

struct Options {
    std::vector<std::string> partials, outputs, layers;
    std::string save_partial;
    double exposure = 0;
    bool require_complete = false, quiet = false;
};

void add_options(CLI::App &app, Options &o) {
    app.add_option("PARTIAL", o.partials, "partial renders (.ppmpart) of one render")->type_name("");
    app.add_option("-o,--output", o.outputs,
                   "image to write, repeatable: .exr (linear float radiance),\n"
                   ".png, .jpg, .tif (sRGB 8-bit); written atomically")
        ->type_name("PATH")
        ->allow_extra_args(false); // one path per -o: a partial after it stays a partial
    app.add_option("--exposure", o.exposure, "scales 8-bit images by 2^EV before sRGB encoding\n(default 0)")
        ->check(CLI::Range(-100.0, 100.0))
        ->type_name("EV");
    app.add_option("--layers", o.layers,
                   "extra EXR channels, comma separated: radius (mean\n"
                   "gather radius), photons (photons found in all passes)")
        ->delimiter(',')
        ->check(CLI::IsMember({"radius", "photons"}))
        ->type_name("LIST")
        ->allow_extra_args(false);
    app.add_option("--save-partial", o.save_partial, "also save the merged partial (to merge further, or\nto resume)")
        ->type_name("PATH");
    app.add_flag("--require-complete", o.require_complete,
                 "exit 2 without writing when passes of the render\nare missing");
    app.add_flag("-q,--quiet", o.quiet, "no progress, no summary (errors and warnings are\nstill printed)");
}

void check_options(const Options &o) {
    if (o.partials.empty()) throw ppm_tools::UsageError("no partial render given");
    if (o.outputs.empty() && o.save_partial.empty())
        throw ppm_tools::UsageError("no output given (-o IMAGE or --save-partial)");
}

using ppm_tools::check;

int64_t get_int(ppm_partial p, const char *key) {
    int64_t value = 0;
    check(ppm_partial_get_int(p, key, &value));
    return value;
}

// "0-9, 20, 30-39" of ranges as ppm_partial_get_passes gives them.
std::string describe(const std::vector<uint64_t> &ranges) {
    std::string text;
    for (std::size_t k = 0; k + 1 < ranges.size(); k += 2) {
        text += text.empty() ? "" : ", ";
        text += std::to_string(ranges[k]);
        if (ranges[k + 1] - ranges[k] > 1) text += "-" + std::to_string(ranges[k + 1] - 1);
    }
    return text;
}

// The ranges of [0, total) that `held` (sorted ranges) lacks.
std::vector<uint64_t> missing_passes(const std::vector<uint64_t> &held, uint64_t total) {
    std::vector<uint64_t> missing;
    uint64_t next = 0;
    for (std::size_t k = 0; k + 1 < held.size() && next < total; k += 2) {
        if (held[k] > next) missing.push_back(next), missing.push_back(std::min(held[k], total));
        next = held[k + 1];
    }
    if (next < total) missing.push_back(next), missing.push_back(total);
    return missing;
}

int merge(const Options &options) {
    for (const std::string &path : options.outputs) check_image_format(path);
    const bool progress = !options.quiet && isatty(STDERR_FILENO);
    ppm_tools::Partial merged;
    for (std::size_t i = 0; i < options.partials.size(); ++i) {
        const std::string &path = options.partials[i];
        ppm_tools::Partial part;
        check(ppm_partial_load(path.c_str(), part.out()));
        if (!merged)
            merged = std::move(part);
        else
            check(ppm_partial_merge(merged, part));
        if (progress)
            std::fprintf(stderr, "\rppm-merge: %zu of %zu partials, %lld passes", i + 1, options.partials.size(),
                         static_cast<long long>(get_int(merged, "passes")));
    }
    if (progress) std::fputc('\n', stderr);

    const int64_t passes = get_int(merged, "passes"), total = get_int(merged, "pass_total");
    std::vector<uint64_t> held(2 * static_cast<std::size_t>(get_int(merged, "pass_ranges")));
    std::size_t count = 0;
    check(ppm_partial_get_passes(merged, held.data(), held.size(), &count));
    const std::vector<uint64_t> missing = missing_passes(held, static_cast<uint64_t>(total));
    if (!missing.empty()) {
        std::fprintf(stderr, "ppm-merge: %s: passes %s of the render's %lld are missing%s\n",
                     options.require_complete ? "error" : "warning", describe(missing).c_str(),
                     static_cast<long long>(total),
                     options.require_complete ? "" : "; the image is the mean of the passes present");
        if (options.require_complete) return 2;
    }

    Image image;
    image.width = static_cast<int>(get_int(merged, "width"));
    image.height = static_cast<int>(get_int(merged, "height"));
    const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
    image.radiance.resize(3 * pixels);
    check(ppm_partial_get_layer(merged, "radiance", image.radiance.data(), image.radiance.size()));
    for (const std::string &name : options.layers) {
        image.layers.push_back(Layer{name, std::vector<float>(pixels)});
        check(ppm_partial_get_layer(merged, name.c_str(), image.layers.back().data.data(), pixels));
    }
    for (const std::string &path : options.outputs) write_image_atomically(path, image, options.exposure);
    if (!options.save_partial.empty()) check(ppm_partial_save(merged, options.save_partial.c_str()));
    if (!options.quiet) {
        std::string outputs;
        for (const std::string &path : options.outputs) outputs += (outputs.empty() ? "" : ", ") + path;
        if (!options.save_partial.empty())
            outputs += (outputs.empty() ? "partial " : ", partial ") + options.save_partial;
        std::fprintf(stderr, "ppm-merge: %zu partials, passes %s (%lld in all), %d x %d -> %s\n",
                     options.partials.size(), describe(held).c_str(), static_cast<long long>(passes), image.width,
                     image.height, outputs.c_str());
    }
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    CLI::App app(description, "ppm-merge");
    ppm_tools::configure(app, footer);
    Options options;
    add_options(app, options);
    const int parsed = ppm_tools::parse(app, argc, argv);
    if (parsed >= 0) return parsed;
    try {
        check_options(options);
    } catch (const ppm_tools::UsageError &e) {
        return ppm_tools::report_usage_error(app, e.what());
    }
    try {
        return merge(options);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ppm-merge: %s\n", e.what());
    }
    return ppm_tools::kExitRuntime;
}

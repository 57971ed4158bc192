// ppm-merge: merges the partial renders of one render (ppm-render --pass-range ... --partial)
// into its image, exactly: the merge of passes 0..N-1 is the image one process rendering N
// passes would give, bit for bit, whatever the split and order.
#include <ppm/ppm.h>

#include "image_writer.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

using namespace ppm_render;

namespace {

const char *const usage_text =
    "usage: ppm-merge PARTIAL... -o OUTPUT [-o OUTPUT]... [options]\n"
    "Merges partial renders (ppm-render --pass-range A:B --partial PATH) of one render into\n"
    "its image. Partials of another scene, camera or settings, or with a pass in common, are\n"
    "refused. Merging an incomplete set writes the image of the passes present (their mean)\n"
    "and names the missing ones.\n"
    "\n"
    "  -o, --output PATH     image to write, repeatable: .exr (linear float radiance), .png,\n"
    "                        .jpg, .tif (sRGB 8-bit); written atomically\n"
    "  --exposure EV         scales 8-bit images by 2^EV before sRGB encoding (default 0)\n"
    "  --layers LIST         extra EXR channels, comma separated: radius (mean gather radius),\n"
    "                        photons (photons found in all passes)\n"
    "  --save-partial PATH   also save the merged partial (to merge further, or to resume)\n"
    "  --require-complete    exit 2 without writing when passes of the render are missing\n"
    "  -q, --quiet           no progress, no summary (errors and warnings are still printed)\n"
    "  --version             print the libppm version\n"
    "  -h, --help            this text\n"
    "Exit status: 0 done, 1 usage error, 2 runtime error (a bad, foreign or overlapping\n"
    "partial, an unwritable image, missing passes with --require-complete).\n";

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Options {
    std::vector<std::string> partials, outputs, layers;
    std::string save_partial;
    double exposure = 0;
    bool require_complete = false, quiet = false, help = false, version = false;
};

Options parse_options(int argc, char **argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw UsageError(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "-h" || arg == "--help") {
            o.help = true;
        } else if (arg == "--version") {
            o.version = true;
        } else if (arg == "-q" || arg == "--quiet") {
            o.quiet = true;
        } else if (arg == "-o" || arg == "--output") {
            o.outputs.push_back(value());
        } else if (arg == "--exposure") {
            const std::string text = value();
            char *end = nullptr;
            o.exposure = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0' || !std::isfinite(o.exposure) || std::fabs(o.exposure) > 100)
                throw UsageError("--exposure needs a number of stops in [-100, 100], not '" + text + "'");
        } else if (arg == "--layers") {
            std::string list = value() + ",";
            for (std::size_t start = 0, comma; (comma = list.find(',', start)) != std::string::npos;
                 start = comma + 1) {
                const std::string layer = list.substr(start, comma - start);
                if (layer.empty()) continue;
                if (layer != "radius" && layer != "photons")
                    throw UsageError("--layers: unknown layer '" + layer + "' (layers: radius, photons)");
                o.layers.push_back(layer);
            }
        } else if (arg == "--save-partial") {
            o.save_partial = value();
        } else if (arg == "--require-complete") {
            o.require_complete = true;
        } else if (!arg.empty() && arg[0] == '-') {
            throw UsageError("unknown option '" + arg + "'");
        } else {
            o.partials.push_back(arg);
        }
    }
    if (o.help || o.version) return o;
    if (o.partials.empty()) throw UsageError("no partial render given");
    if (o.outputs.empty() && o.save_partial.empty()) throw UsageError("no output given (-o IMAGE or --save-partial)");
    return o;
}

struct RuntimeError {
    std::string message;
};

void check(ppm_status status, const std::string &what = "") {
    if (status != PPM_OK) throw RuntimeError{(what.empty() ? "" : what + ": ") + ppm_last_error_message()};
}

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
    ppm_partial merged = nullptr;
    struct Release {
        ppm_partial &p;
        ~Release() { ppm_partial_release(p); }
    } release{merged};
    for (std::size_t i = 0; i < options.partials.size(); ++i) {
        const std::string &path = options.partials[i];
        ppm_partial part = nullptr;
        check(ppm_partial_load(path.c_str(), &part));
        if (!merged) {
            merged = part;
        } else {
            const ppm_status status = ppm_partial_merge(merged, part);
            ppm_partial_release(part);
            check(status);
        }
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
    Options options;
    try {
        options = parse_options(argc, argv);
    } catch (const UsageError &e) {
        std::fprintf(stderr, "ppm-merge: %s\nTry 'ppm-merge -h' for help.\n", e.what());
        return 1;
    }
    if (options.help) {
        std::fputs(usage_text, stdout);
        return 0;
    }
    if (options.version) {
        std::printf("ppm-merge (libppm %s)\n", ppm_version_string());
        return 0;
    }
    try {
        return merge(options);
    } catch (const RuntimeError &e) {
        std::fprintf(stderr, "ppm-merge: %s\n", e.message.c_str());
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ppm-merge: %s\n", e.what());
    }
    return 2;
}

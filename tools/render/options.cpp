#include "options.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace ppm_render {

const char *const usage_text =
    "usage: ppm-render SCENE.json [-o OUTPUT]... [options]\n"
    "Renders a scene file (docs/scene-format.md) by progressive photon mapping. The image is\n"
    "rewritten atomically as the render converges, so it can be watched and is never lost.\n"
    "\n"
    "output:\n"
    "  -o, --output PATH     image to write, repeatable: .exr (linear float radiance), .png,\n"
    "                        .jpg/.jpeg, .tif (sRGB 8-bit with --exposure); default\n"
    "                        <scene name>.png in the current folder\n"
    "  --exposure EV         scales 8-bit images by 2^EV before sRGB encoding (default 0)\n"
    "  --layers LIST         extra EXR channels, comma separated: radius (gather radius in\n"
    "                        scene units), photons (the alpha-reduced photon count N)\n"
    "  --write-interval S    rewrite the images at most every S seconds (default 1; 0: after\n"
    "                        every pass); they are always written at the end\n"
    "rendering (override the scene file's integrator):\n"
    "  --passes N            total passes (default: integrator.passes, else 16, or unlimited\n"
    "                        with --time)\n"
    "  --photons N           photon paths per pass\n"
    "  --time SECONDS        wall-clock budget: no pass starts that would end after it, and a\n"
    "                        pass still running at the deadline is abandoned\n"
    "  --seed N              random sequence (same seed and passes: same image)\n"
    "  --threads N           worker threads (default: all)\n"
    "  --set KEY=VALUE       any renderer setting (mode, alpha, initial_radius, max_depth,\n"
    "                        hit_point_search, direct_lighting, ...), repeatable\n"
    "checkpoints:\n"
    "  --checkpoint PATH     where checkpoints go (default <first output>.ppmckpt); written on\n"
    "                        SIGINT/SIGTERM, every --checkpoint-interval, and at the end when\n"
    "                        this option is given\n"
    "  --checkpoint-interval S  seconds between periodic checkpoints (default 300; 0: never)\n"
    "  --resume PATH         continue a render from its checkpoint: with the same scene and\n"
    "                        options, the result equals the uninterrupted render\n"
    "render farms (passes rendered apart and merged exactly with ppm-merge):\n"
    "  --pass-range A:B      render passes A .. B-1 of the --passes N (0 <= A < B <= N) in\n"
    "                        the pass-independent mode \"pppm\"; needs --partial\n"
    "  --partial PATH        save the passes as a partial render (.ppmpart) instead of an\n"
    "                        image (images only with -o); it is also the checkpoint, so\n"
    "                        --resume PATH goes on with the missing passes of the range\n"
    "other:\n"
    "  -q, --quiet           no progress bar, no summary (errors are still printed)\n"
    "  --version             print the libppm version\n"
    "  -h, --help            this text\n"
    "\n"
    "SIGINT or SIGTERM (Ctrl-C) abandons the running pass, writes the images and a checkpoint\n"
    "and exits 0; a second one exits at once. The progress bar (pass, photons/s, ETA) goes to\n"
    "stderr when it is a terminal.\n"
    "Exit status: 0 done (also when interrupted), 1 usage error (options), 2 runtime error\n"
    "(a bad or missing scene file, setting or checkpoint, an unwritable image).\n";

namespace {

double parse_number(const std::string &option, const char *text, double low) {
    char *end = nullptr;
    const double value = std::strtod(text, &end);
    if (end == text || *end != '\0' || !std::isfinite(value) || value < low)
        throw UsageError(option + " needs a number >= " + std::to_string(static_cast<long long>(low)) + ", not '" +
                         text + "'");
    return value;
}

std::int64_t parse_integer(const std::string &option, const char *text, std::int64_t low, std::int64_t high) {
    char *end = nullptr;
    errno = 0;
    const long long value = std::strtoll(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || value < low || value > high)
        throw UsageError(option + " needs a whole number in " + std::to_string(low) + " .. " + std::to_string(high) +
                         ", not '" + text + "'");
    return value;
}

std::vector<std::string> split_list(const std::string &text) {
    std::vector<std::string> items;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = text.find(',', start);
        const std::size_t end = comma == std::string::npos ? text.size() : comma;
        if (end > start) items.push_back(text.substr(start, end - start));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return items;
}

} // namespace

Options parse_options(int argc, char **argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const auto value = [&]() -> const char * {
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
            const char *text = value();
            char *end = nullptr;
            o.exposure = std::strtod(text, &end);
            if (end == text || *end != '\0' || !std::isfinite(o.exposure) || std::fabs(o.exposure) > 100)
                throw UsageError("--exposure needs a number of stops in [-100, 100], not '" + std::string(text) + "'");
        } else if (arg == "--layers") {
            for (const std::string &layer : split_list(value())) {
                if (layer != "radius" && layer != "photons")
                    throw UsageError("--layers: unknown layer '" + layer + "' (layers: radius, photons)");
                o.layers.push_back(layer);
            }
        } else if (arg == "--write-interval") {
            o.write_interval = parse_number(arg, value(), 0);
        } else if (arg == "--passes") {
            o.passes = parse_integer(arg, value(), 1, std::int64_t(1) << 40);
        } else if (arg == "--photons") {
            o.photons = parse_integer(arg, value(), 1, std::int64_t(1) << 31);
        } else if (arg == "--time") {
            o.time = parse_number(arg, value(), 0);
        } else if (arg == "--seed") {
            o.seed = parse_integer(arg, value(), 0, std::int64_t(1) << 53);
        } else if (arg == "--threads") {
            o.threads = parse_integer(arg, value(), 1, 1024);
        } else if (arg == "--set") {
            const std::string setting = value();
            const std::size_t equals = setting.find('=');
            if (equals == std::string::npos || equals == 0 || equals + 1 == setting.size())
                throw UsageError("--set needs KEY=VALUE, not '" + setting + "'");
            o.settings.emplace_back(setting.substr(0, equals), setting.substr(equals + 1));
        } else if (arg == "--checkpoint") {
            o.checkpoint = value();
            o.checkpoint_given = true;
        } else if (arg == "--checkpoint-interval") {
            o.checkpoint_interval = parse_number(arg, value(), 0);
        } else if (arg == "--resume") {
            o.resume = value();
        } else if (arg == "--pass-range") {
            const std::string text = value();
            const std::size_t colon = text.find(':');
            if (colon == std::string::npos)
                throw UsageError("--pass-range needs A:B (passes A .. B-1), not '" + text + "'");
            o.pass_first = parse_integer(arg, text.substr(0, colon).c_str(), 0, std::int64_t(1) << 32);
            o.pass_end = parse_integer(arg, text.substr(colon + 1).c_str(), 1, std::int64_t(1) << 32);
            if (o.pass_first >= o.pass_end)
                throw UsageError("--pass-range " + text + " is empty: A must be below B (passes A .. B-1)");
        } else if (arg == "--partial") {
            o.partial = value();
        } else if (!arg.empty() && arg[0] == '-') {
            throw UsageError("unknown option '" + arg + "'");
        } else if (o.scene.empty()) {
            o.scene = arg;
        } else {
            throw UsageError("more than one scene file given ('" + o.scene + "' and '" + arg + "')");
        }
    }
    if (o.help || o.version) return o;
    if (o.scene.empty()) throw UsageError("no scene file given");
    if (o.pass_first >= 0 && !o.partial_render())
        throw UsageError("--pass-range needs --partial PATH: the passes are saved as a partial render");
    if (o.pass_first >= 0 && o.passes > 0 && o.pass_end > o.passes)
        throw UsageError("--pass-range " + std::to_string(o.pass_first) + ":" + std::to_string(o.pass_end) +
                         " goes beyond --passes " + std::to_string(o.passes));
    if (o.partial_render()) {
        for (const auto &[key, value] : o.settings)
            if (key == "mode" && value != "pppm")
                throw UsageError("--partial renders in mode pppm (pass-independent), not --set mode=" + value);
        if (o.checkpoint_given)
            throw UsageError("--partial PATH is the checkpoint of a partial render; --checkpoint is not needed");
        o.checkpoint = o.partial;
        return o;
    }
    if (o.outputs.empty()) {
        std::string name = o.scene.substr(o.scene.rfind('/') == std::string::npos ? 0 : o.scene.rfind('/') + 1);
        const std::size_t dot = name.rfind('.');
        if (dot != std::string::npos && dot > 0) name.resize(dot);
        o.outputs.push_back(name + ".png");
    }
    if (o.checkpoint.empty()) {
        std::string base = o.outputs.front();
        const std::size_t dot = base.rfind('.');
        if (dot != std::string::npos && dot > 0 && base.find('/', dot) == std::string::npos) base.resize(dot);
        o.checkpoint = base + ".ppmckpt";
    }
    return o;
}

} // namespace ppm_render

// SPDX-License-Identifier: Apache-2.0
// BSDF values for comparisons with other renderers (tools/validate/compare_dielectric_bsdfs.py):
// reads one query per line from stdin and prints one answer line.
//   E <material> <mode> wo.x wo.y wo.z wi.x wi.y wi.z  ->  f.r f.g f.b pdf
//   A <material> <mode> wo.x wo.y wo.z <samples>       ->  mean sample weight (r g b), the albedo
//   S <material> <mode> wo.x wo.y wo.z <u_lobe>        ->  wi.x wi.y wi.z pdf weight.r specular
// <material> is ten words: type (thindielectric, roughdielectric, roughplastic) distribution
// (beckmann, ggx) alpha_u alpha_v int_ior ext_ior reflectance (one grey value) sample_visible
// (0/1) nonlinear (0/1) specular_reflectance (one grey value); <mode> is radiance or
// importance.
#include "material/bsdf.h"
#include "material/microfacet.h"

#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

using namespace ppm;

namespace {

uint64_t state = 0x1234567ULL;
double uniform() { // splitmix64
    uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return ((z ^ (z >> 31)) >> 11) * 0x1p-53;
}

Bsdf read_material(std::istream &in, TransportMode *mode) {
    std::string type, dist, mode_name;
    double au, av, int_ior, ext_ior, refl, specular;
    int visible, nonlinear;
    in >> type >> dist >> au >> av >> int_ior >> ext_ior >> refl >> visible >> nonlinear >> specular >> mode_name;
    MicrofacetType t = MicrofacetType::Beckmann;
    parse_microfacet_type(dist.c_str(), &t);
    *mode = mode_name == "importance" ? TransportMode::Importance : TransportMode::Radiance;
    if (type == "thindielectric") return Bsdf::thin_dielectric(int_ior, ext_ior);
    if (type == "roughdielectric") return Bsdf::rough_dielectric(t, au, av, int_ior, ext_ior, visible != 0);
    return Bsdf::rough_plastic(Rgb(refl), t, au, int_ior, ext_ior, visible != 0, nonlinear != 0, Rgb(specular));
}

} // namespace

int main() {
    std::string line;
    while (std::getline(std::cin, line)) {
        std::istringstream in(line);
        std::string op;
        in >> op;
        TransportMode mode;
        const Bsdf b = read_material(in, &mode);
        Vec3 wo;
        in >> wo.x >> wo.y >> wo.z;
        if (op == "E") {
            Vec3 wi;
            in >> wi.x >> wi.y >> wi.z;
            const Rgb f = b.eval(wo, wi, mode);
            std::printf("%.17g %.17g %.17g %.17g\n", f.r, f.g, f.b, b.pdf(wo, wi));
        } else if (op == "A") {
            long n;
            in >> n;
            double sum[3] = {0, 0, 0};
            for (long k = 0; k < n; ++k) {
                const double u0 = uniform(), u1 = uniform(), u2 = uniform();
                const BsdfSample s = b.sample(wo, u0, u1, u2, mode);
                if (!s.valid()) continue;
                sum[0] += s.weight.r, sum[1] += s.weight.g, sum[2] += s.weight.b;
            }
            std::printf("%.17g %.17g %.17g\n", sum[0] / n, sum[1] / n, sum[2] / n);
        } else {
            double u_lobe;
            in >> u_lobe;
            const BsdfSample s = b.sample(wo, u_lobe, 0.5, 0.5, mode);
            std::printf("%.17g %.17g %.17g %.17g %.17g %d\n", s.wi.x, s.wi.y, s.wi.z, s.pdf, s.weight.r,
                        s.is_specular ? 1 : 0);
        }
        std::fflush(stdout);
    }
    return 0;
}

// SPDX-License-Identifier: Apache-2.0
// Multiple importance sampling between the techniques of vertex connection and merging
// (Georgiev, Krivanek, Davidovic and Slusallek 2012, "Light transport simulation with vertex
// connection and merging", and its technical report's recursive form, the one SmallVCM uses).
//
// A full path of k segments can be made by many techniques: a camera subpath that hits a light
// (emitter hit), one that connects to a point sampled on a light (next event), a light subpath
// that connects to the camera (light tracing), a camera and a light subpath joined by a
// segment (connection), or a camera vertex merged with a light vertex within the radius r
// (merging, one per interior non-specular vertex). The balance heuristic weighs technique i by
// p_i / sum_j p_j, every p in area measure; merging counts with p_connect * pi r^2 * L for L
// light subpaths per pass. Instead of walking the whole path for every weight, each subpath
// carries three running sums (SubpathMis) of the ratios p_j / p_own of the techniques that
// split it at an earlier vertex, so each weight costs O(1):
//   dvcm: the ratio of the technique that would have made the last vertex from the other side,
//   dvc:  the connection techniques' ratios summed over the earlier vertices,
//   dvm:  the merging techniques' ratios summed over the earlier vertices.
// Every density is a solid-angle density of a BSDF (forward: in the subpath's direction;
// reverse: the other way) or a light's (light.h EmissionDensities), times the Russian roulette
// continuation probability of the vertex; conversions to area measure are the cosines and
// squared distances passed in. Balance heuristic throughout (power 1).
#pragma once

namespace ppm {

// What a pass's techniques share: the merging and connection factors, from the merge radius
// and the light subpath count. A technique that is switched off has factor 0.
struct MisFactors {
    double vm_weight = 0; // pi r^2 L, if merging is on
    double vc_weight = 0; // 1 / (pi r^2 L), if connections are on
    double light_paths = 1;

    static MisFactors make(double radius, double light_paths, bool connect, bool merge) {
        const double eta = 3.14159265358979323846 * radius * radius * light_paths;
        MisFactors f;
        f.vm_weight = merge ? eta : 0.0;
        f.vc_weight = connect ? 1.0 / eta : 0.0;
        f.light_paths = light_paths;
        return f;
    }
};

struct SubpathMis {
    double dvcm = 0, dvc = 0, dvm = 0;

    // A light subpath leaving its light: `emission` and `direct` are the light's densities
    // (EmissionDensities) times the probability of picking the light.
    static SubpathMis light_start(const MisFactors &f, double emission, double direct, double cos_light,
                                  bool delta_light, bool finite_light) {
        SubpathMis m;
        m.dvcm = direct / emission;
        m.dvc = delta_light ? 0.0 : (finite_light ? cos_light : 1.0) / emission;
        m.dvm = m.dvc * f.vc_weight;
        return m;
    }
    // A camera subpath, its first direction drawn with solid-angle density camera_pdf_w; 0
    // when light subpaths are not connected to the camera (the light tracing technique is off).
    static SubpathMis camera_start(const MisFactors &f, double camera_pdf_w) {
        SubpathMis m;
        m.dvcm = camera_pdf_w > 0 ? f.light_paths / camera_pdf_w : 0.0;
        return m;
    }

    // The subpath reaches a vertex after a segment of squared length dist2 arriving at cosine
    // |cos_here|. dist2 is not applied (pass 0) on the first segment from a light at infinity,
    // whose densities are per area of its disc, not of the first hit's surface.
    void arrive(double dist2, double cos_here) {
        if (dist2 > 0) dvcm *= dist2;
        const double inv = 1.0 / cos_here;
        dvcm *= inv;
        dvc *= inv;
        dvm *= inv;
    }

    // The subpath scatters: `pdf_fwd` and `pdf_rev` are the solid-angle densities of the sampled
    // direction and of the arriving one sampled back (both times the continuation
    // probability), cos_out the cosine of the sampled direction. Specular lobes: no technique
    // can join the path at this vertex, and their densities cancel.
    void scatter(const MisFactors &f, bool specular, double cos_out, double pdf_fwd, double pdf_rev) {
        if (specular) {
            dvcm = 0;
            dvc *= cos_out;
            dvm *= cos_out;
            return;
        }
        const double g = cos_out / pdf_fwd;
        dvc = g * (dvc * pdf_rev + dvcm + f.vm_weight);
        dvm = g * (dvm * pdf_rev + dvcm * f.vc_weight + 1.0);
        dvcm = 1.0 / pdf_fwd;
    }
};

// The weights. Each is 1 / (1 + the other techniques' summed ratios).

// A camera subpath (not the camera's first segment) hits an emitter. direct_pdf_a and
// emission_pdf_w: the light's densities at the hit (times the pick probability).
inline double mis_emitter_hit(const SubpathMis &camera, double direct_pdf_a, double emission_pdf_w) {
    return 1.0 / (1.0 + direct_pdf_a * camera.dvcm + emission_pdf_w * camera.dvc);
}

// Next event: a camera vertex connected to a point sampled on a light. bsdf_fwd and bsdf_rev:
// the camera vertex's densities towards the light and back along its arriving direction
// (times the continuation probability; bsdf_fwd is 0 for a delta light, which no BSDF sample
// hits). pick: the light's pick probability; direct_pdf_w, emission_pdf, cos_light: the
// sample's (LightIllumination, without pick); cos_camera: at the camera vertex.
inline double mis_next_event(const MisFactors &f, const SubpathMis &camera, double bsdf_fwd, double bsdf_rev,
                             double pick, double direct_pdf_w, double emission_pdf, double cos_light,
                             double cos_camera) {
    const double w_light = bsdf_fwd / (pick * direct_pdf_w);
    const double w_camera =
        emission_pdf * cos_camera / (direct_pdf_w * cos_light) * (f.vm_weight + camera.dvcm + camera.dvc * bsdf_rev);
    return 1.0 / (w_light + 1.0 + w_camera);
}

// A light vertex connected to the camera. camera_pdf_a: the density of the camera's ray
// through the vertex, per area at the vertex; bsdf_rev: the light vertex's density of its
// arriving direction, sampled back from the camera's (times continuation).
inline double mis_light_trace(const MisFactors &f, const SubpathMis &light, double camera_pdf_a, double bsdf_rev) {
    const double w_light = camera_pdf_a / f.light_paths * (f.vm_weight + light.dvcm + light.dvc * bsdf_rev);
    return 1.0 / (w_light + 1.0);
}

// A camera vertex connected to a light vertex. *_fwd_a: the density, in area measure at the
// other vertex, of each side sampling the other (pdf_w |cos there| / dist^2); *_rev_w: each
// side's density of its own arriving direction sampled back from the connecting one.
inline double mis_connection(const MisFactors &f, const SubpathMis &camera, const SubpathMis &light,
                             double camera_fwd_a, double camera_rev_w, double light_fwd_a, double light_rev_w) {
    const double w_light = camera_fwd_a * (f.vm_weight + light.dvcm + light.dvc * light_rev_w);
    const double w_camera = light_fwd_a * (f.vm_weight + camera.dvcm + camera.dvc * camera_rev_w);
    return 1.0 / (w_light + 1.0 + w_camera);
}

// A camera vertex merged with a light vertex. camera_fwd_w: the camera vertex's density of
// the light vertex's arriving direction; camera_rev_w: of its own arriving direction sampled
// back from that one (both times continuation).
inline double mis_merge(const MisFactors &f, const SubpathMis &camera, const SubpathMis &light, double camera_fwd_w,
                        double camera_rev_w) {
    const double w_light = light.dvcm * f.vc_weight + light.dvm * camera_fwd_w;
    const double w_camera = camera.dvcm * f.vc_weight + camera.dvm * camera_rev_w;
    return 1.0 / (w_light + 1.0 + w_camera);
}

} // namespace ppm

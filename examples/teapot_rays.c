/* SPDX-License-Identifier: Apache-2.0 */
/*
 * teapot_rays: a complete libppm program in one screen or two.
 *
 * It loads a .bpt file of bicubic Bezier patches, shoots a grid of pinhole-camera rays at it
 * in one batch, casts a shadow ray from every hit, and prints the picture as ASCII art shaded
 * by the surface normal. Then it prints the details of the first hit.
 *
 * The scene is framed from its bounding box and viewed from the front (-y) and a little
 * above, with +z up: the orientation of the Utah teapot in tests/data/teapot.bpt.
 *
 * Every fallible libppm call returns a ppm_status (PPM_OK == 0); on failure
 * ppm_last_error_message() says what was wrong and where.
 *
 * Usage: teapot_rays FILE.bpt        exit status 0 ok, 1 usage error, 2 runtime error
 */
#include <ppm/ppm.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Image size in characters. A character cell is about twice as tall as it is wide, so the
 * picture covers a region of aspect WIDTH : 2 * HEIGHT. */
enum { WIDTH = 64, HEIGHT = 20 };

/* Prints why a call failed. The message must be read before the next ppm_* call on this
 * thread, which may overwrite it, so it is printed first. Returns 1 if `status` is a failure. */
static int failed(ppm_status status, const char *what) {
    if (status == PPM_OK) return 0;
    fprintf(stderr, "teapot_rays: %s failed: %s", what, ppm_last_error_message());
    fprintf(stderr, " (%s)\n", ppm_status_string(status));
    return 1;
}

static void normalize(double v[3]) {
    double length = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= length;
    v[1] /= length;
    v[2] /= length;
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

int main(int argc, char **argv) {
    if (argc != 2 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        fprintf(argc == 2 ? stdout : stderr,
                "usage: %s FILE.bpt\n"
                "Ray traces the Bezier patches in FILE.bpt (e.g. tests/data/teapot.bpt) with "
                "libppm and prints them as ASCII art.\n",
                argv[0]);
        return argc == 2 ? 0 : 1;
    }
    if (strcmp(argv[1], "--version") == 0) {
        /* PPM_VERSION_STRING is the header we compiled against, ppm_version_string() the
         * library actually loaded. */
        printf("teapot_rays, built with libppm %s, running libppm %s\n", PPM_VERSION_STRING, ppm_version_string());
        return 0;
    }

    int exit_code = 2;
    ppm_context context = NULL; /* *_release(NULL) is a no-op, so cleanup needs no checks */
    ppm_scene scene = NULL;
    ppm_ray *rays = malloc(sizeof(ppm_ray) * WIDTH * HEIGHT);
    ppm_hit *hits = malloc(sizeof(ppm_hit) * WIDTH * HEIGHT);
    ppm_ray *shadow_rays = malloc(sizeof(ppm_ray) * WIDTH * HEIGHT);
    size_t *shadow_pixel = malloc(sizeof(size_t) * WIDTH * HEIGHT);
    uint8_t *in_shadow = malloc(WIDTH * HEIGHT);
    if (!rays || !hits || !shadow_rays || !shadow_pixel || !in_shadow) {
        fprintf(stderr, "teapot_rays: out of memory\n");
        goto cleanup;
    }

    /* 1. A context (Embree device and worker threads), and a scene in it. */
    if (failed(ppm_context_create(&context), "ppm_context_create")) goto cleanup;
    if (failed(ppm_scene_create(context, &scene), "ppm_scene_create")) goto cleanup;

    /* 2. Geometry. The patches are intersected exactly (to the scene's "tolerance", relative
     *    to the scene's size; 1e-9 by default), not tessellated. */
    uint32_t geom_id;
    if (failed(ppm_scene_load_bpt(scene, argv[1], &geom_id), "ppm_scene_load_bpt")) goto cleanup;
    size_t patch_count;
    if (failed(ppm_scene_get_primitive_count(scene, geom_id, &patch_count), "ppm_scene_get_primitive_count"))
        goto cleanup;

    /* 3. Commit builds the acceleration structure; only then may the scene be queried. */
    if (failed(ppm_scene_commit(scene), "ppm_scene_commit")) goto cleanup;
    double lower[3], upper[3], tolerance;
    if (failed(ppm_scene_get_bounds(scene, lower, upper), "ppm_scene_get_bounds")) goto cleanup;
    if (failed(ppm_scene_get_double(scene, "tolerance", &tolerance), "ppm_scene_get_double")) goto cleanup;
    printf("%s: %zu patches, bounds (%g %g %g) - (%g %g %g), tolerance %g\n", argv[1], patch_count, lower[0], lower[1],
           lower[2], upper[0], upper[1], upper[2], tolerance);

    /* 4. A pinhole camera looking at the centre of the bounds from the front (-y) and a
     *    little above: forward is along +y and slightly down, right is +x, up is close to +z.
     *    The field of view just takes in the eight corners of the bounding box. */
    double center[3], radius2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        center[k] = 0.5 * (lower[k] + upper[k]);
        radius2 += 0.25 * (upper[k] - lower[k]) * (upper[k] - lower[k]);
    }
    double forward[3] = {0.0, 1.0, -0.35};
    normalize(forward);
    const double right[3] = {1.0, 0.0, 0.0};
    const double up[3] = {right[1] * forward[2] - right[2] * forward[1], right[2] * forward[0] - right[0] * forward[2],
                          right[0] * forward[1] - right[1] * forward[0]};
    double eye[3];
    for (int k = 0; k < 3; ++k) eye[k] = center[k] - 3.0 * sqrt(radius2) * forward[k];
    const double aspect = 2.0 * HEIGHT / WIDTH;
    double half_width = 0.0; /* of the image plane at distance 1 from the eye */
    for (int corner = 0; corner < 8; ++corner) {
        double to_corner[3];
        for (int k = 0; k < 3; ++k) to_corner[k] = ((corner >> k) & 1 ? upper[k] : lower[k]) - eye[k];
        double depth = dot(to_corner, forward);
        half_width = fmax(half_width, fabs(dot(to_corner, right)) / depth);
        half_width = fmax(half_width, fabs(dot(to_corner, up)) / depth / aspect);
    }

    for (int row = 0; row < HEIGHT; ++row) {
        for (int col = 0; col < WIDTH; ++col) {
            double sx = (2.0 * (col + 0.5) / WIDTH - 1.0) * half_width;
            double sy = (1.0 - 2.0 * (row + 0.5) / HEIGHT) * half_width * aspect;
            ppm_ray *ray = &rays[row * WIDTH + col];
            for (int k = 0; k < 3; ++k) {
                ray->org[k] = eye[k];
                ray->dir[k] = forward[k] + sx * right[k] + sy * up[k]; /* need not be unit */
            }
            ray->tnear = 0.0;
            ray->tfar = INFINITY;
        }
    }

    /* 5. Closest hits of all rays in one call (large batches run on the worker threads). */
    if (failed(ppm_scene_intersect(scene, rays, (size_t)WIDTH * HEIGHT, hits), "ppm_scene_intersect")) goto cleanup;

    /* 6. Shadow rays towards a distant light. ppm_hit_spawn_ray moves the origin off the
     *    surface by the hit's error bound so the ray does not hit its own starting point. */
    double to_light[3] = {-1.0, -0.7, 1.0};
    normalize(to_light);
    size_t shadow_count = 0;
    for (size_t i = 0; i < (size_t)WIDTH * HEIGHT; ++i) {
        if (hits[i].geom_id == PPM_INVALID_ID) continue;
        if (failed(ppm_hit_spawn_ray(&hits[i], to_light, &shadow_rays[shadow_count]), "ppm_hit_spawn_ray"))
            goto cleanup;
        shadow_pixel[shadow_count++] = i;
    }
    memset(in_shadow, 0, WIDTH * HEIGHT);
    if (shadow_count > 0) {
        uint8_t *occluded = malloc(shadow_count);
        if (!occluded) {
            fprintf(stderr, "teapot_rays: out of memory\n");
            goto cleanup;
        }
        ppm_status status = ppm_scene_occluded(scene, shadow_rays, shadow_count, occluded);
        for (size_t s = 0; status == PPM_OK && s < shadow_count; ++s) in_shadow[shadow_pixel[s]] = occluded[s];
        free(occluded);
        if (failed(status, "ppm_scene_occluded")) goto cleanup;
    }

    /* 7. ASCII art: Lambert shading of the shading normal turned towards the viewer (patches
     *    are two-sided and the teapot's are not consistently oriented), ambient in shadow. */
    static const char ramp[] = ".:-=+*#%@";
    const int levels = (int)sizeof ramp - 1;
    size_t first_hit = (size_t)-1;
    for (int row = 0; row < HEIGHT; ++row) {
        char line[WIDTH + 1];
        for (int col = 0; col < WIDTH; ++col) {
            size_t i = (size_t)row * WIDTH + col;
            const ppm_hit *hit = &hits[i];
            if (hit->geom_id == PPM_INVALID_ID) {
                line[col] = ' ';
                continue;
            }
            if (first_hit == (size_t)-1) first_hit = i;
            double n[3] = {hit->ns[0], hit->ns[1], hit->ns[2]};
            if (dot(n, rays[i].dir) > 0.0) {
                n[0] = -n[0];
                n[1] = -n[1];
                n[2] = -n[2];
            }
            double lambert = in_shadow[i] ? 0.0 : dot(n, to_light);
            double shade = 0.1 + 0.9 * (lambert > 0.0 ? lambert : 0.0);
            int level = (int)(shade * levels);
            line[col] = ramp[level < levels ? level : levels - 1];
        }
        line[WIDTH] = '\0';
        printf("|%s|\n", line);
    }

    if (first_hit == (size_t)-1) {
        printf("no ray hit the scene\n");
    } else {
        const ppm_hit *hit = &hits[first_hit];
        printf("first hit (row %zu, column %zu): t = %.17g\n", first_hit / WIDTH, first_hit % WIDTH, hit->t);
        printf("  patch %u of geometry %u at (u, v) = (%.17g, %.17g)\n", hit->prim_id, hit->geom_id, hit->u, hit->v);
        printf("  point (%.9f, %.9f, %.9f) +- %.3g\n", hit->p[0], hit->p[1], hit->p[2], hit->p_error);
        printf("  normal (%.9f, %.9f, %.9f)\n", hit->ng[0], hit->ng[1], hit->ng[2]);
    }
    exit_code = 0;

cleanup:
    /* Handles may be released in any order: the scene keeps its context alive. */
    ppm_scene_release(scene);
    ppm_context_release(context);
    free(in_shadow);
    free(shadow_pixel);
    free(shadow_rays);
    free(hits);
    free(rays);
    return exit_code;
}

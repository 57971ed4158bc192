// SPDX-License-Identifier: Apache-2.0
// Image textures through OpenImageIO: an 8-bit PNG is decoded from sRGB to linear, v = 0 is
// the top row, lookups are bilinear between texel centres and repeat outside [0, 1); bad
// files give clear errors.
#include "io/obj_reader.h"
#include "material/material.h"
#include "material/texture.h"

#include "core/error.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <unistd.h>

#include "test_support.h" // last: cmocka defines macros such as fail()

using namespace ppm;

namespace {

std::string temp_path(const char *name) { return "/tmp/ppm_test_texture_" + std::to_string(getpid()) + "_" + name; }

// 2 x 2 RGB image: top row (255, 0, 0) (0, 255, 0), bottom row (0, 0, 255) (128, 128, 128).
std::string write_png() {
    const std::string path = temp_path("tiny.png");
    const unsigned char pixels[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128};
    auto out = OIIO::ImageOutput::create(path);
    assert_non_null(out.get());
    OIIO::ImageSpec spec(2, 2, 3, OIIO::TypeDesc::UINT8);
    assert_true(out->open(path, spec));
    assert_true(out->write_image(OIIO::TypeDesc::UINT8, pixels));
    out->close();
    return path;
}

void srgb_png_decodes_to_linear_with_top_row_at_v0(void **) {
    const std::string path = write_png();
    const auto texture = Texture::load(path);
    assert_int_equal(texture->width(), 2);
    // Texel centres are at u, v = 0.25 and 0.75.
    const Rgb top_left = texture->lookup(0.25, 0.25), bottom_right = texture->lookup(0.75, 0.75);
    assert_close(top_left.r, 1.0, 1e-6);
    assert_close(top_left.g, 0.0, 1e-6);
    assert_close(bottom_right.r, srgb_to_linear(128 / 255.0), 1e-6); // 0.2158, not 0.502
    assert_close(srgb_to_linear(128 / 255.0), 0.21586, 1e-4);
    const Rgb bottom_left = texture->lookup(0.25, 0.75);
    assert_close(bottom_left.b, 1.0, 1e-6);
    // Halfway between the top texels: the mean of red and green; repeat wraps u + 3.
    const Rgb mid = texture->lookup(0.5, 0.25);
    assert_close(mid.r, 0.5, 1e-6);
    assert_close(mid.g, 0.5, 1e-6);
    const Rgb wrapped = texture->lookup(3.25, -0.75);
    assert_close(wrapped.r, top_left.r, 1e-9);
    // At u = 0 the left and right columns blend (the texture repeats).
    assert_close(texture->lookup(0.0, 0.25).r, 0.5, 1e-6);
    std::remove(path.c_str());
}

void material_applies_mapping_and_keeps_energy(void **) {
    const auto texture = std::make_shared<Texture>(1, 1, std::vector<float>{2.0f, 0.5f, 0.25f}, "bright");
    Material m{Bsdf::diffuse(Rgb(0.1)), TextureRef::bitmap(texture, TextureMapping::scale_offset(4, 4, 0.1, 0.2))};
    const Bsdf b = m.at(0.3, 0.7);
    assert_close(b.reflectance().r, 1.0, 0); // clamped: a reflectance above 1 would create energy
    assert_close(b.reflectance().g, 0.5, 1e-7);
    assert_close(b.reflectance().b, 0.25, 1e-7);
}

// A 4 x 1 image of values 0, 1, 2, 3 (grey): index arithmetic is easy to check.
std::shared_ptr<const Texture> ramp() {
    return std::make_shared<Texture>(4, 1, std::vector<float>{0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3}, "ramp");
}

// Nearest takes the texel under (u, v): floor(u * width), no half-texel shift (Mitsuba 3).
void nearest_filter_takes_the_texel_under_uv(void **) {
    const auto t = ramp();
    const TextureFilter n = TextureFilter::Nearest;
    assert_close(t->lookup(0.0, 0.5, n).r, 0, 0);
    assert_close(t->lookup(0.24, 0.5, n).r, 0, 0);
    assert_close(t->lookup(0.26, 0.5, n).r, 1, 0);
    assert_close(t->lookup(0.99, 0.5, n).r, 3, 0);
    assert_close(t->lookup(1.1, 0.5, n, TextureWrap::Repeat).r, 0, 0);  // texel 4 -> 0
    assert_close(t->lookup(1.1, 0.5, n, TextureWrap::Mirror).r, 3, 0);  // texel 4 -> 3
    assert_close(t->lookup(1.3, 0.5, n, TextureWrap::Mirror).r, 2, 0);  // texel 5 -> 2
    assert_close(t->lookup(-0.1, 0.5, n, TextureWrap::Mirror).r, 0, 0); // texel -1 -> 0
    assert_close(t->lookup(-0.3, 0.5, n, TextureWrap::Mirror).r, 1, 0); // texel -2 -> 1
    assert_close(t->lookup(1.9, 0.5, n, TextureWrap::Mirror).r, 0, 0);  // texel 7 -> 0
    assert_close(t->lookup(2.1, 0.5, n, TextureWrap::Mirror).r, 0, 0);  // texel 8 -> 0 (period 2)
    assert_close(t->lookup(-5.0, 0.5, n, TextureWrap::Clamp).r, 0, 0);
    assert_close(t->lookup(7.0, 0.5, n, TextureWrap::Clamp).r, 3, 0);
}

// Bilinear weights the two texels around u * width - 0.5; each wrap mode picks the
// neighbour beyond the edge.
void bilinear_filter_wraps_each_neighbour(void **) {
    const auto t = ramp();
    const TextureFilter b = TextureFilter::Bilinear;
    assert_close(t->lookup(0.125, 0.5, b).r, 0, 1e-12);                      // centre of texel 0
    assert_close(t->lookup(0.25, 0.5, b).r, 0.5, 1e-12);                     // halfway 0 -> 1
    assert_close(t->lookup(0.5, 0.5, b).r, 1.5, 1e-12);                      // halfway 1 -> 2
    assert_close(t->lookup(0.0, 0.5, b, TextureWrap::Repeat).r, 1.5, 1e-12); // (3 + 0) / 2
    assert_close(t->lookup(0.0, 0.5, b, TextureWrap::Mirror).r, 0, 1e-12);   // (0 + 0) / 2
    assert_close(t->lookup(0.0, 0.5, b, TextureWrap::Clamp).r, 0, 1e-12);
    assert_close(t->lookup(1.0, 0.5, b, TextureWrap::Repeat).r, 1.5, 1e-12);
    assert_close(t->lookup(1.0, 0.5, b, TextureWrap::Mirror).r, 3, 1e-12); // (3 + 3) / 2
    assert_close(t->lookup(1.0, 0.5, b, TextureWrap::Clamp).r, 3, 1e-12);
    assert_close(t->lookup(1.125, 0.5, b, TextureWrap::Mirror).r, 3, 1e-12); // texel 4 = 3
    assert_close(t->lookup(1.25, 0.5, b, TextureWrap::Mirror).r, 2.5, 1e-12);
    assert_close(t->lookup(-3.0, 0.5, b, TextureWrap::Clamp).r, 0, 1e-12);
    assert_close(t->lookup(0.9375, 0.5, b, TextureWrap::Clamp).r, 3, 1e-12);     // past the last centre
    assert_close(t->lookup(0.9375, 0.5, b, TextureWrap::Repeat).r, 2.25, 1e-12); // 3 * 0.75 + 0 * 0.25
}

// raw keeps an 8-bit PNG's stored values (128 / 255), the default decodes sRGB.
void raw_keeps_stored_values(void **) {
    const std::string path = write_png();
    const auto decoded = Texture::load(path), raw = Texture::load(path, true);
    const TextureFilter n = TextureFilter::Nearest;
    assert_close(decoded->lookup(0.75, 0.75, n).g, srgb_to_linear(128 / 255.0), 1e-6);
    assert_close(raw->lookup(0.75, 0.75, n).g, 128 / 255.0, 1e-6);
    assert_close(raw->lookup(0.25, 0.25, n).r, 1.0, 0);
    std::remove(path.c_str());
}

// to_uv's full 2D affine map: a quarter turn u = -t + 1, v = s sends (s, t) = (0.1, 0.9)
// to (0.1, 0.1), so the top left texel (red) of the 2 x 2 PNG.
void to_uv_rotation(void **) {
    const std::string path = write_png();
    TextureMapping turn;
    turn.m[0][0] = 0;
    turn.m[0][1] = -1;
    turn.m[0][2] = 1;
    turn.m[1][0] = 1;
    turn.m[1][1] = 0;
    turn.m[1][2] = 0;
    const TextureRef t = TextureRef::bitmap(Texture::load(path), turn, TextureFilter::Nearest);
    const Rgb red = t.eval(0.1, 0.9), green = t.eval(0.1, 0.4), blue = t.eval(0.9, 0.9);
    assert_close(red.r, 1, 0);
    assert_close(green.g, 1, 0); // (u, v) = (0.6, 0.1): top right
    assert_close(blue.b, 1, 0);  // (u, v) = (0.1, 0.9): bottom left
    double u, v;
    TextureMapping::scale_offset(2, 3, 0.5, 0.25).apply(1, 1, &u, &v);
    assert_close(u, 2.5, 0);
    assert_close(v, 3.25, 0);
    std::remove(path.c_str());
}

// Mitsuba 3 checkerboard: color0 where frac(u) and frac(v) are both > 0.5 or both not.
void checkerboard_cells(void **) {
    const TextureRef c = TextureRef::checkerboard(Rgb(0.4), Rgb(0.2));
    assert_close(c.eval(0.25, 0.25).r, 0.4, 0);
    assert_close(c.eval(0.75, 0.75).r, 0.4, 0);
    assert_close(c.eval(0.75, 0.25).r, 0.2, 0);
    assert_close(c.eval(0.25, 0.75).r, 0.2, 0);
    assert_close(c.eval(0.5, 0.25).r, 0.4, 0);   // exactly 0.5 is not > 0.5
    assert_close(c.eval(-0.25, 0.25).r, 0.2, 0); // frac(-0.25) = 0.75
    const TextureRef scaled =
        TextureRef::checkerboard(Rgb(1, 0, 0), Rgb(0, 0, 1), TextureMapping::scale_offset(4, 4, 0, 0));
    assert_close(scaled.eval(0.2, 0.05).b, 1, 0); // u = 0.8, v = 0.2
    assert_close(scaled.eval(0.3, 0.05).r, 1, 0); // u = 1.2
    // As a scalar (eval_1: weights, opacities) Mitsuba swaps the cells: color1 at (0.1, 0.1).
    assert_close(TextureRef::checkerboard(Rgb(1), Rgb(0)).eval_1(0.1, 0.1), 0, 0);
    assert_close(TextureRef::checkerboard(Rgb(1), Rgb(0)).eval_1(0.7, 0.1), 1, 1e-6);
    assert_close(TextureRef::checkerboard(Rgb(0, 1, 0), Rgb(0)).eval_1(0.7, 0.1), 0.715160, 1e-12);
    // A checkerboard textures a material like an image.
    const Material m{Bsdf::diffuse(Rgb(0.5)), scaled};
    assert_close(m.at(0.2, 0.05).reflectance().b, 1, 0);
}

void bad_files_are_clear_errors(void **) {
    try {
        Texture::load("/no/such/dir/texture.png");
        fail_msg("missing file loaded");
    } catch (const Error &e) {
        assert_int_equal(e.status(), PPM_ERROR_IO);
        assert_non_null(std::strstr(e.what(), "/no/such/dir/texture.png"));
    }
    const std::string path = temp_path("garbage.png");
    std::FILE *f = std::fopen(path.c_str(), "wb");
    std::fputs("\x89PNG\r\n\x1a\nthis is not a png", f);
    std::fclose(f);
    try {
        Texture::load(path);
        fail_msg("garbage loaded");
    } catch (const Error &e) {
        assert_int_equal(e.status(), PPM_ERROR_IO);
        assert_non_null(std::strstr(e.what(), "garbage.png"));
    }
    std::remove(path.c_str());
}

// Runs load(path) with stderr sent to a file; returns what was written there.
std::string stderr_of_load(const std::string &path, ppm_status *status, std::string *message) {
    const std::string captured = temp_path("stderr.txt");
    std::fflush(stderr);
    const int saved = dup(2);
    std::FILE *sink = std::fopen(captured.c_str(), "wb");
    assert_non_null(sink);
    dup2(fileno(sink), 2);
    *status = PPM_OK;
    try {
        Texture::load(path);
    } catch (const Error &e) {
        *status = e.status();
        *message = e.what();
    }
    std::fflush(stderr);
    dup2(saved, 2);
    close(saved);
    std::fclose(sink);
    std::FILE *in = std::fopen(captured.c_str(), "rb");
    std::string text;
    for (int c; (c = std::fgetc(in)) != EOF;) text += static_cast<char>(c);
    std::fclose(in);
    std::remove(captured.c_str());
    return text;
}

// A PNG cut short (an interrupted copy) is an IO error naming the file and the cut, and
// neither libpng nor OpenImageIO prints anything or leaks (the ASan build checks the leak).
void truncated_png_is_a_quiet_io_error(void **) {
    const std::string whole = temp_path("whole.png");
    {
        unsigned char pixels[16 * 16 * 3];
        for (size_t i = 0; i < sizeof pixels; ++i) pixels[i] = static_cast<unsigned char>(i * 7 % 251);
        auto out = OIIO::ImageOutput::create(whole);
        assert_non_null(out.get());
        assert_true(out->open(whole, OIIO::ImageSpec(16, 16, 3, OIIO::TypeDesc::UINT8)));
        assert_true(out->write_image(OIIO::TypeDesc::UINT8, pixels));
        out->close();
    }
    std::FILE *in = std::fopen(whole.c_str(), "rb");
    std::string bytes;
    for (int c; (c = std::fgetc(in)) != EOF;) bytes += static_cast<char>(c);
    std::fclose(in);
    std::remove(whole.c_str());
    assert_true(bytes.size() > 100);

    // Cut inside the image data, and cut just before the closing IEND chunk (12 bytes).
    const size_t cuts[2] = {bytes.size() / 2, bytes.size() - 12};
    const char *expected[2] = {"runs to byte", "no IEND chunk"};
    for (int k = 0; k < 2; ++k) {
        const std::string path = temp_path("truncated.png");
        std::FILE *f = std::fopen(path.c_str(), "wb");
        std::fwrite(bytes.data(), 1, cuts[k], f);
        std::fclose(f);
        ppm_status status;
        std::string message;
        const std::string printed = stderr_of_load(path, &status, &message);
        std::remove(path.c_str());
        assert_int_equal(status, PPM_ERROR_IO);
        assert_non_null(std::strstr(message.c_str(), "truncated.png' is a truncated PNG"));
        assert_non_null(std::strstr(message.c_str(), expected[k]));
        assert_string_equal(printed.c_str(), "");
    }
}

// An OpenEXR header attribute whose size runs past the end of the file is refused before
// OpenEXR allocates it (23 bytes claiming a 1.8 GB string); a real EXR still loads.
void exr_attribute_beyond_the_file_is_refused(void **) {
    const std::string path = temp_path("attribute.exr");
    std::FILE *f = std::fopen(path.c_str(), "wb");
    std::fwrite("v/1\x01\x02\x00\x00\x00"
                "a\x00string\x00\x7c\x00\x00\x6fxx",
                1, 23, f);
    std::fclose(f);
    try {
        Texture::load(path);
        fail_msg("corrupt EXR loaded");
    } catch (const Error &e) {
        assert_int_equal(e.status(), PPM_ERROR_IO);
        assert_non_null(std::strstr(e.what(), "attribute.exr' is a corrupt or truncated OpenEXR file: its header "
                                              "attribute 'a' claims 1862271100 bytes, the file has 23"));
    }
    const float pixels[12] = {0.5f, 1, 2, 0, 0, 0, 1, 1, 1, 4, 3, 2};
    auto out = OIIO::ImageOutput::create(path);
    assert_non_null(out.get());
    assert_true(out->open(path, OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::HALF)));
    assert_true(out->write_image(OIIO::TypeDesc::FLOAT, pixels));
    out->close();
    const auto texture = Texture::load(path);
    assert_close(texture->lookup(0.25, 0.25).b, 2.0, 1e-6);
    std::remove(path.c_str());
}

// A header that claims more pixels than the file's bytes can hold is refused before anything
// of that size is allocated (here 10000 x 10000 RGB, 300 MB, from a file of 19 bytes).
void oversized_header_is_refused_before_allocating(void **) {
    const std::string path = temp_path("huge.ppm");
    std::FILE *f = std::fopen(path.c_str(), "wb");
    std::fputs("P6\n10000 10000\n255\n", f);
    std::fclose(f);
    try {
        Texture::load(path);
        fail_msg("oversized texture loaded");
    } catch (const Error &e) {
        if (e.status() != PPM_ERROR_PARSE) fail_msg("status %d: %s", e.status(), e.what());
        assert_non_null(
            std::strstr(e.what(), "its header claims 10000 x 10000 pixels, more than its 19 bytes can hold"));
    }
    std::remove(path.c_str());
}

} // namespace

// OBJ's vt puts v = 0 at the image's bottom row; libppm (like Mitsuba) at the top: the reader
// turns vt (u, v) into (u, 1 - v), so an OBJ textured by any other tool looks the same here.
static void obj_texture_coordinates_follow_the_obj_convention(void **) {
    const ppm::MeshData mesh =
        ppm::parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0.25\nvt 0 1\nf 1/1 2/2 3/3\n", "uv.obj");
    assert_int_equal(mesh.uvs.size(), 6);
    const double expected[6] = {0, 1, 1, 0.75, 0, 0};
    for (int i = 0; i < 6; ++i) assert_close(mesh.uvs[i], expected[i], 0);
}

int main() {
    const CMUnitTest tests[] = {
        cmocka_unit_test(srgb_png_decodes_to_linear_with_top_row_at_v0),
        cmocka_unit_test(material_applies_mapping_and_keeps_energy),
        cmocka_unit_test(nearest_filter_takes_the_texel_under_uv),
        cmocka_unit_test(bilinear_filter_wraps_each_neighbour),
        cmocka_unit_test(raw_keeps_stored_values),
        cmocka_unit_test(to_uv_rotation),
        cmocka_unit_test(checkerboard_cells),
        cmocka_unit_test(bad_files_are_clear_errors),
        cmocka_unit_test(truncated_png_is_a_quiet_io_error),
        cmocka_unit_test(exr_attribute_beyond_the_file_is_refused),
        cmocka_unit_test(oversized_header_is_refused_before_allocating),
        cmocka_unit_test(obj_texture_coordinates_follow_the_obj_convention),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}

// What a C++ renderer does with biref: shade a surface hit in world space, and read the slab's
// Jones matrices as std::complex. Prints JSON (the power fractions match `biref slab --json`).
#include <biref/biref.h>

#include <cmath>
#include <cstdio>
#include <memory>

int main()
{
    const double pi = 3.14159265358979323846;
    const double theta = 30.0 * pi / 180.0;

    // The slab frame of `biref slab`: surface y = 0, light in the YZ plane, angles in radians.
    biref_slab slab{1.775, 1.231, {0.084, 0.979, -0.187}, 1.15e6, 1.0};
    biref_jones T, R;
    if (biref_status st = biref_slab_jones(&slab, theta, 550.0, &T, &R); st != BIREF_OK) {
        char msg[BIREF_MSG_SIZE] = "";
        biref_slab_check(&slab, msg, sizeof msg); // the reason, if the slab is the problem
        std::fprintf(stderr, "shade_hit: %s\n", msg[0] ? msg : biref_status_string(st));
        return 1;
    }

    // One spectral context per process, and one shader (method, light) for the whole frame
    // (analytic method, unpolarized light: the nullptr defaults); RAII releases both, the shader
    // first.
    char msg[256];
    biref_spectral *raw_sp = nullptr;
    if (biref_spectral_create(nullptr, &raw_sp, msg, sizeof msg) != BIREF_OK) {
        std::fprintf(stderr, "shade_hit: %s\n", msg);
        return 1;
    }
    std::unique_ptr<biref_spectral, decltype(&biref_spectral_destroy)> sp(raw_sp, biref_spectral_destroy);
    biref_shader *raw = nullptr;
    if (biref_shader_create(sp.get(), nullptr, nullptr, &raw, msg, sizeof msg) != BIREF_OK) {
        std::fprintf(stderr, "shade_hit: %s\n", msg);
        return 1;
    }
    std::unique_ptr<biref_shader, decltype(&biref_shader_destroy)> shader(raw, biref_shader_destroy);

    // A slab tilted in the world: normal, tangent, optic axis in the slab's local frame.
    biref_surface surface{{0.0, 0.8, 0.6}, {1.0, 0.0, 0.0}, {0.084, 0.979, -0.187}, 1.775, 1.231, 5000.0, 1.0};
    const double view[3] = {0.3, -0.9, -0.2}; // camera -> hit
    double t_xyz[3], r_xyz[3];
    biref_hit_frames frames;
    if (biref_status st = biref_shade_hit(shader.get(), &surface, view, t_xyz, r_xyz, &frames); st != BIREF_OK) {
        std::fprintf(stderr, "shade_hit: %s\n", biref_status_string(st));
        return 1;
    }
    double t_rgb[3], r_rgb[3];
    biref_xyz_to_srgb(t_xyz, t_rgb);
    biref_xyz_to_srgb(r_xyz, r_rgb);

    std::printf("{\n  \"T\": {");
    const char *sp_name[2] = {"s", "p"};
    for (int in = 0; in < 2; in++)
        std::printf("\"%s\": {\"s\": %.17g, \"p\": %.17g}%s", sp_name[in], std::norm(T.m[in][0]), std::norm(T.m[in][1]),
                    in ? "},\n" : ", ");
    std::printf("  \"R\": {");
    for (int in = 0; in < 2; in++)
        std::printf("\"%s\": {\"s\": %.17g, \"p\": %.17g}%s", sp_name[in], std::norm(R.m[in][0]), std::norm(R.m[in][1]),
                    in ? "},\n" : ", ");
    std::printf("  \"hit_theta_deg\": %.6f,\n", frames.theta * 180.0 / pi);
    std::printf("  \"hit_srgb_T\": [%.6f, %.6f, %.6f],\n", t_rgb[0], t_rgb[1], t_rgb[2]);
    std::printf("  \"hit_srgb_R\": [%.6f, %.6f, %.6f]\n}\n", r_rgb[0], r_rgb[1], r_rgb[2]);
    return std::isfinite(t_rgb[0]) ? 0 : 1;
}

/* Native back-end: a headless OpenGL >= 4.3 core context through EGL, the scene drawn as one
 * full-screen pass of shaders/biref_analytic.glsl into a float XYZ target, GPU time from a
 * timer query. libepoxy resolves EGL and GL entry points at run time. */
#include <dlfcn.h>
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/gpu.h"
#include "gl_context.h"
#include "biref/material.h"

/* Array sizes compiled into the native shader: the scene format's own limits. */
#define GL_MAX_SLABS BIREF_SCENE_MAX_SLABS
#define GL_MAX_PANELS BIREF_SCENE_MAX_PANELS
/* Rows per draw call: keeps each submission short on drivers with a watchdog. */
#define BAND_ROWS 256

struct gl_context {
    EGLDisplay dpy;
    EGLContext ctx;
    EGLSurface surf;
    GLuint prog, vao, lut, plans, subbands, material; /* subbands: made for the first dispersive scene */
    biref_spectral *sp; /* the table's source and constants, kept for the uniforms */
    char desc[256];
};

static biref_status fail(char *msg, size_t msg_len, const char *fmt, ...)
{
    if (msg && msg_len) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, msg_len, fmt, ap);
        va_end(ap);
    }
    return BIREF_ERR_IO;
}

static GLuint compile(GLenum type, const char *defines, char *msg, size_t msg_len)
{
    const char *src[3] = {"#version 430 core\n", defines, biref_gl_shader_source()};
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, 3, src, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        for (char *c = log; *c; c++)
            if (*c == '\n') *c = ' ';
        fail(msg, msg_len, "OpenGL: shader does not compile: %s", log);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

static biref_status build_program(gl_context *g, char *msg, size_t msg_len)
{
    char defs[160];
    snprintf(defs, sizeof defs, "#define BIREF_FRAGMENT\n#define BIREF_SCENE\n#define BIREF_MAX_SLABS %d\n#define BIREF_MAX_PANELS %d\n",
             GL_MAX_SLABS, GL_MAX_PANELS);
    GLuint vs = compile(GL_VERTEX_SHADER, "#define BIREF_VERTEX\n", msg, msg_len);
    if (!vs) return BIREF_ERR_IO;
    GLuint fs = compile(GL_FRAGMENT_SHADER, defs, msg, msg_len);
    if (!fs) {
        glDeleteShader(vs);
        return BIREF_ERR_IO;
    }
    g->prog = glCreateProgram();
    glAttachShader(g->prog, vs);
    glAttachShader(g->prog, fs);
    glLinkProgram(g->prog);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(g->prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetProgramInfoLog(g->prog, sizeof log, NULL, log);
        for (char *c = log; *c; c++)
            if (*c == '\n') *c = ' ';
        return fail(msg, msg_len, "OpenGL: shader does not link: %s", log);
    }
    return BIREF_OK;
}

static biref_status upload_table(gl_context *g, char *msg, size_t msg_len)
{
    char why[BIREF_MSG_SIZE];
    if (biref_spectral_create(NULL, &g->sp, why, sizeof why) != BIREF_OK)
        return fail(msg, msg_len, "cannot build the look-up table: %s", why);
    biref_gl_table_info info;
    biref_gl_table(g->sp, &info, NULL);
    float *tex = malloc((size_t)info.width * info.height * 4 * sizeof *tex);
    if (!tex) return fail(msg, msg_len, "out of memory");
    biref_gl_table(g->sp, &info, tex);
    glGenTextures(1, &g->lut);
    glBindTexture(GL_TEXTURE_2D, g->lut);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, info.width, info.height, 0, GL_RGBA, GL_FLOAT, tex);
    free(tex);
    /* The coherent regime's sample plans. */
    biref_gl_plans_info pl;
    biref_gl_coherent_plans(g->sp, &pl, NULL);
    tex = malloc((size_t)pl.width * pl.height * 4 * sizeof *tex);
    if (!tex) return fail(msg, msg_len, "out of memory");
    biref_gl_coherent_plans(g->sp, &pl, tex);
    glGenTextures(1, &g->plans);
    glBindTexture(GL_TEXTURE_2D, g->plans);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, pl.width, pl.height, 0, GL_RGBA, GL_FLOAT, tex);
    free(tex);
    return glGetError() == GL_NO_ERROR ? BIREF_OK : fail(msg, msg_len, "OpenGL: cannot create the look-up textures");
}

/* A context on one display: OpenGL >= 4.3 core, current, surfaceless when the driver allows it
 * (we draw into a framebuffer object), else on a 1x1 pbuffer. */
static biref_status make_current(gl_context *g, char *msg, size_t msg_len)
{
    EGLConfig cfg;
    EGLint n = 0;
    const EGLint cfg_attr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    const EGLint cfg_any[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    if (!eglBindAPI(EGL_OPENGL_API) || ((!eglChooseConfig(g->dpy, cfg_attr, &cfg, 1, &n) || n < 1) &&
                                        (!eglChooseConfig(g->dpy, cfg_any, &cfg, 1, &n) || n < 1)))
        return fail(msg, msg_len, "EGL: no configuration for desktop OpenGL");
    const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    g->ctx = eglCreateContext(g->dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (g->ctx == EGL_NO_CONTEXT)
        return fail(msg, msg_len, "EGL: no OpenGL 4.3 core context (EGL error 0x%x)", (unsigned)eglGetError());
    if (!eglMakeCurrent(g->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, g->ctx)) {
        const EGLint pb[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        g->surf = eglCreatePbufferSurface(g->dpy, cfg, pb);
        if (g->surf == EGL_NO_SURFACE || !eglMakeCurrent(g->dpy, g->surf, g->surf, g->ctx))
            return fail(msg, msg_len, "EGL: cannot make the OpenGL context current");
    }
    if (epoxy_gl_version() < 43)
        return fail(msg, msg_len, "OpenGL %d.%d found, the gl back-end needs OpenGL >= 4.3", epoxy_gl_version() / 10,
                    epoxy_gl_version() % 10);
    return BIREF_OK;
}

static void release_context(gl_context *g)
{
    if (g->ctx != EGL_NO_CONTEXT) {
        eglMakeCurrent(g->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(g->dpy, g->ctx);
    }
    if (g->surf != EGL_NO_SURFACE) eglDestroySurface(g->dpy, g->surf);
    g->ctx = EGL_NO_CONTEXT;
    g->surf = EGL_NO_SURFACE;
}

#define MAX_DEVICES 16

/* Candidate displays, best first: each hardware EGL device (a real GPU, without a window
 * system), Mesa's surfaceless platform (its GPU, or llvmpipe where there is none), the default
 * display. Returns the number written. */
static int candidate_displays(EGLDisplay out[MAX_DEVICES + 2])
{
    int n = 0;
    const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    /* Looked up by hand: libepoxy dispatches client extensions by a display's version. */
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    PFNEGLQUERYDEVICESEXTPROC query_devices = (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    PFNEGLQUERYDEVICESTRINGEXTPROC device_string =
        (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
    if (!ext || !get_platform_display) return 0;
    if (strstr(ext, "EGL_EXT_platform_device") && query_devices && device_string) {
        EGLDeviceEXT dev[MAX_DEVICES];
        EGLint nd = 0;
        if (query_devices(MAX_DEVICES, dev, &nd))
            for (EGLint i = 0; i < nd; i++) {
                const char *dext = device_string(dev[i], EGL_EXTENSIONS);
                if (dext && strstr(dext, "EGL_MESA_device_software")) continue; /* llvmpipe: below */
                EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, dev[i], NULL);
                if (d != EGL_NO_DISPLAY) out[n++] = d;
            }
    }
    if (strstr(ext, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
        if (d != EGL_NO_DISPLAY) out[n++] = d;
    }
    return n;
}

biref_status gl_context_create(gl_context **out, char *msg, size_t msg_len)
{
    *out = NULL;
    /* libepoxy aborts the process when it cannot load libEGL: look first. */
    void *egl = dlopen("libEGL.so.1", RTLD_LAZY | RTLD_LOCAL);
    if (!egl) return fail(msg, msg_len, "no EGL library (libEGL.so.1) on this machine: the gl back-end needs EGL and OpenGL >= 4.3");
    dlclose(egl);
    gl_context *g = calloc(1, sizeof *g);
    if (!g) return fail(msg, msg_len, "out of memory");
    g->dpy = EGL_NO_DISPLAY;
    g->ctx = EGL_NO_CONTEXT;
    g->surf = EGL_NO_SURFACE;
    EGLDisplay cand[MAX_DEVICES + 2];
    int n = candidate_displays(cand);
    cand[n++] = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    biref_status s = fail(msg, msg_len, "EGL: no display could be initialised (no OpenGL driver?)");
    for (int i = 0; i < n; i++) {
        if (cand[i] == EGL_NO_DISPLAY || !eglInitialize(cand[i], NULL, NULL)) continue;
        g->dpy = cand[i];
        if ((s = make_current(g, msg, msg_len)) == BIREF_OK) break;
        release_context(g);
        g->dpy = EGL_NO_DISPLAY;
    }
    if (s) goto out;
    snprintf(g->desc, sizeof g->desc, "%s, %s, %s", (const char *)glGetString(GL_VENDOR),
             (const char *)glGetString(GL_RENDERER), (const char *)glGetString(GL_VERSION));
    if ((s = build_program(g, msg, msg_len)) || (s = upload_table(g, msg, msg_len))) goto out;
    glGenVertexArrays(1, &g->vao);
    *out = g;
    return BIREF_OK;
out:
    gl_context_destroy(g);
    return s;
}

void gl_context_destroy(gl_context *g)
{
    if (!g) return;
    if (g->ctx != EGL_NO_CONTEXT && eglGetCurrentContext() == g->ctx) {
        if (g->prog) glDeleteProgram(g->prog);
        if (g->lut) glDeleteTextures(1, &g->lut);
        if (g->plans) glDeleteTextures(1, &g->plans);
        if (g->subbands) glDeleteTextures(1, &g->subbands);
        if (g->material) glDeleteTextures(1, &g->material);
        if (g->vao) glDeleteVertexArrays(1, &g->vao);
    }
    release_context(g);
    /* The display stays initialised: EGL displays are process-wide (another object or library
     * may be using the same one), and terminating it unloads the driver, whose caches then
     * show up as leaks of an unknown module under LeakSanitizer. */
    eglReleaseThread();
    biref_spectral_destroy(g->sp);
    free(g);
}

const char *gl_context_description(const gl_context *g) { return g->desc; }

/* An RGBA float texture of nearest texels (*tex made on the first call, refilled after). */
static void float_texture(GLuint *tex, int width, int height, const float *texels)
{
    if (!*tex) glGenTextures(1, tex);
    glBindTexture(GL_TEXTURE_2D, *tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, texels);
}

/* The scene's dispersive materials (biref_gl_scene_materials) and, for the first scene that has
 * one, the sub-band tables; a scene without one gets a texel of zeros (never read). */
static biref_status upload_materials(gl_context *g, const biref_scene *scene, char *msg, size_t msg_len)
{
    biref_gl_material_info mi;
    biref_gl_scene_materials(scene, g->sp, &mi, NULL);
    if (mi.dispersive && !g->subbands) {
        biref_gl_subband_info si;
        biref_gl_subband_table(g->sp, &si, NULL);
        float *t = malloc((size_t)si.width * si.height * 4 * sizeof *t);
        if (!t || biref_gl_subband_table(g->sp, &si, t) != BIREF_OK) {
            free(t);
            return fail(msg, msg_len, "out of memory for the sub-band tables");
        }
        float_texture(&g->subbands, si.width, si.height, t);
        free(t);
    }
    const float zero[4] = {0, 0, 0, 0};
    if (!mi.dispersive) {
        float_texture(&g->material, 1, 1, zero);
        if (!g->subbands) float_texture(&g->subbands, 1, 1, zero);
        return glGetError() == GL_NO_ERROR ? BIREF_OK : fail(msg, msg_len, "OpenGL: cannot create the material textures");
    }
    float *t = malloc((size_t)mi.width * mi.height * 4 * sizeof *t);
    if (!t) return fail(msg, msg_len, "out of memory for the materials' indices");
    biref_status s = biref_gl_scene_materials(scene, g->sp, &mi, t);
    if (s == BIREF_OK) float_texture(&g->material, mi.width, mi.height, t);
    free(t);
    if (s != BIREF_OK) {
        /* The CPU renderer's check and message (slabs[i].material: why). */
        biref_gl_table_info ti;
        biref_gl_table(g->sp, &ti, NULL);
        char why[BIREF_MSG_SIZE] = "unphysical within the band";
        for (int i = 0; i < scene->n_slabs; i++)
            if (scene->slabs[i].material &&
                biref_material_check_band(scene->slabs[i].material, ti.lambda_min_nm, ti.lambda_max_nm, why,
                                          sizeof why) != BIREF_OK)
                return fail(msg, msg_len, "slabs[%d].material: %s", i, why);
        return fail(msg, msg_len, "a slab's material: %s", why);
    }
    return glGetError() == GL_NO_ERROR ? BIREF_OK : fail(msg, msg_len, "OpenGL: cannot create the material textures");
}

static void set_uniform(void *user, const char *name, int comps, int count, const float *v)
{
    GLint loc = glGetUniformLocation(*(GLuint *)user, name);
    if (loc < 0) return; /* unused by this build of the shader */
    switch (comps) {
    case 1: glUniform1fv(loc, count, v); break;
    case 2: glUniform2fv(loc, count, v); break;
    case 3: glUniform3fv(loc, count, v); break;
    default: glUniform4fv(loc, count, v); break;
    }
}

biref_status gl_context_render(gl_context *g, const biref_scene *scene, int pairs, float *xyz, double *gpu_ms,
                             biref_render_stats *stats, char *msg, size_t msg_len)
{
    const int W = scene->camera.width, H = scene->camera.height;
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (W > max_size || H > max_size)
        return fail(msg, msg_len, "image %dx%d exceeds the OpenGL texture limit %d", W, H, (int)max_size);
    float *rgba = malloc((size_t)W * H * 4 * sizeof *rgba);
    if (!rgba) return fail(msg, msg_len, "out of memory for a %dx%d image", W, H);

    GLuint tex, fbo, query[2];
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, W, H);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    biref_status s = BIREF_OK;
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        s = fail(msg, msg_len, "OpenGL: cannot render into a %dx%d float target", W, H);
        goto done;
    }
    if ((s = upload_materials(g, scene, msg, msg_len)) != BIREF_OK) goto done;
    glUseProgram(g->prog);
    biref_gl_scene_uniforms(scene, g->sp, set_uniform, &g->prog);
    glUniform1f(glGetUniformLocation(g->prog, "u_pairs"), pairs ? 1.0f : 0.0f);
    const struct {
        GLuint tex;
        const char *name;
    } samplers[] = {{g->lut, "u_lut"}, {g->plans, "u_plans"}, {g->subbands, "u_subbands"}, {g->material, "u_material"}};
    for (int i = 0; i < 4; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, samplers[i].tex);
        glUniform1i(glGetUniformLocation(g->prog, samplers[i].name), i);
    }
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(g->vao);
    glViewport(0, 0, W, H);
    glDisable(GL_BLEND);
    glEnable(GL_SCISSOR_TEST);
    /* Two timestamps rather than GL_TIME_ELAPSED: llvmpipe's first elapsed-time query of a
     * context reports the time since an arbitrary origin. */
    glGenQueries(2, query);
    glQueryCounter(query[0], GL_TIMESTAMP);
    for (int y = 0; y < H; y += BAND_ROWS) {
        glScissor(0, y, W, H - y < BAND_ROWS ? H - y : BAND_ROWS);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glFlush();
    }
    glQueryCounter(query[1], GL_TIMESTAMP);
    glDisable(GL_SCISSOR_TEST);
    GLuint64 t0 = 0, t1 = 0;
    glGetQueryObjectui64v(query[0], GL_QUERY_RESULT, &t0);
    glGetQueryObjectui64v(query[1], GL_QUERY_RESULT, &t1);
    glDeleteQueries(2, query);
    if (gpu_ms) *gpu_ms = (double)(t1 - t0) * 1e-6;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, rgba);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        s = fail(msg, msg_len, "OpenGL error 0x%x while rendering", (unsigned)err);
        goto done;
    }
    long slab = 0, fallback = 0;
    for (int y = 0; y < H; y++) {
        const float *src = rgba + (size_t)(H - 1 - y) * W * 4; /* GL rows are bottom-up */
        float *dst = xyz + (size_t)y * W * 3;
        for (int x = 0; x < W; x++) {
            for (int k = 0; k < 3; k++) dst[3 * x + k] = src[4 * x + k];
            slab += src[4 * x + 3] > 0.5f;
            fallback += src[4 * x + 3] > 1.5f;
        }
    }
    if (stats) {
        stats->pixels = (long)W * H;
        stats->slab_pixels = slab;
        stats->fallback_evals = fallback;
    }
done:
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    free(rgba);
    return s;
}

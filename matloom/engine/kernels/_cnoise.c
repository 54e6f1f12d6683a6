/*
 * _cnoise: optional compiled OpenSimplex (2014) fBm for MatLoom's pure-numpy backend.
 *
 * Why: a one-shot `matloom render` cannot afford numba's import (~0.4 s), and the numpy fBm is
 * the bulk of such a run.  This module loads in microseconds and computes exactly what
 * `noise_numpy.fbm_numpy` computes, bit for bit: every floating-point operation of the numpy
 * code (itself opensimplex 0.4.5.1's `_noise2`, operation by operation) is kept with the same
 * operands in the same order.  Build with `-O3 -ffp-contract=off -fno-fast-math`: a fused
 * multiply-add or any reassociation would change the last bits.  setup.py also passes
 * `-fno-trapping-math` (clang's default): it changes no value, it only lets GCC evaluate both
 * sides of a select so that the loops vectorise (floating-point exception flags are unused here).
 *
 * Plain CPython API only (no numpy C API): arrays arrive through the buffer protocol and must be
 * C-contiguous; the Python wrapper `noise_c.py` prepares them.  The GIL is released in the loops.
 *
 * Float -> int64 conversion of out-of-range floors (NaN, +-inf, |v| >= 2**63) is undefined in C;
 * numpy's conversion result on this platform is probed by the wrapper and passed in as
 * `cast_values` = (value for NaN, value for +overflow, value for -overflow).
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#ifdef __FAST_MATH__
#error "_cnoise must not be built with -ffast-math: results would not match numpy bit for bit"
#endif
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD != 0
#error "_cnoise needs FLT_EVAL_METHOD == 0 (no excess precision, e.g. x87 floating point)"
#endif
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

/* Constants of opensimplex 0.4.5.1 (same literals as matloom/engine/kernels/opensimplex.py). */
static const double STRETCH_CONSTANT2 = -0.211324865405187;
static const double SQUISH_CONSTANT2 = 0.366025403784439;
static const double NORM_CONSTANT2 = 47.0;
/* 2 / sqrt(3), set in module init (sqrt is correctly rounded, like Python's math.sqrt). */
static double FBM_SCALE = 0.0;

/* 2**63: floats in [-2**63, 2**63) convert to int64 exactly (after floor they are integral). */
#define TWO_POW_63 9223372036854775808.0
/* Points per pass; the scratch buffers of one chunk stay in L1. */
#define CHUNK 256

#if defined(__GNUC__)
#define ALWAYS_INLINE static inline __attribute__((always_inline))
#else
#define ALWAYS_INLINE static inline
#endif
/*
 * On x86-64 Linux the loops are compiled twice (baseline x86-64 and AVX2, picked at load time
 * from the CPU): AVX2 does 4 doubles per instruction and has a vector floor.  Both clones do the
 * same IEEE operations (no FMA: -ffp-contract=off), so both give the same bits.
 */
#if !defined(MATLOOM_NO_CPU_CLONES) && defined(__x86_64__) && defined(__linux__) && \
    defined(__GLIBC__) && defined(__GNUC__) && \
    (!defined(__clang__) || __clang_major__ >= 14)
#define CPU_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define CPU_CLONES
#endif

typedef struct {
    unsigned char perm[256];
    /* Low byte (0..255, as a double) of numpy's int64 cast of NaN, +overflow and -overflow. */
    double overflow_low[3];
} NoiseContext;

/* Per-chunk scratch: geometry and vertex keys (pass A), gradient indices (pass B). */
typedef struct {
    double dx0[CHUNK], dy0[CHUNK], ext_x[CHUNK], ext_y[CHUNK], base[CHUNK];
    int32_t key[4][CHUNK];        /* (x & 0xFF) | (y & 0xFF) << 8 of each vertex */
    unsigned char grad[4][CHUNK]; /* perm[...] & 0x0E of each vertex (GRADIENTS2 index) */
} Scratch;

/*
 * Low byte of numpy's `floor_value.astype(np.int64)` (only `& 0xFF` of a lattice coordinate is
 * ever used).  For integral |f| < 2**63, f - 256 * floor(f / 256) is exact (0..255) and
 * vectorises, unlike a float -> int64 conversion.  NaN/inf/|f| >= 2**63 (undefined behaviour in
 * C) take what numpy's cast gives on this platform: `overflow` = (NaN, +big, -big) low bytes.
 * Comparisons are combined with `&`, not `&&`, so that the loop stays branch-free.
 */
ALWAYS_INLINE double low_byte(double f, const double overflow[3])
{
    double r = f - 256.0 * floor(f * 0.00390625);
    int in_range = (f >= -TWO_POW_63) & (f < TWO_POW_63);
    int positive = f > 0.0;
    int negative = f < 0.0;
    double other = positive ? overflow[1] : (negative ? overflow[2] : overflow[0]);
    return in_range ? r : other;
}

/* `((xsb + off_x) & 0xFF) | ((ysb + off_y) & 0xFF) << 8` from the low bytes (wraps like int64). */
ALWAYS_INLINE int32_t vertex_key(int32_t low_x, int32_t low_y, double off_x, double off_y)
{
    int32_t ix = (low_x + (int32_t)off_x) & 0xFF;
    int32_t iy = (low_y + (int32_t)off_y) & 0xFF;
    return ix | (iy << 8);
}

/*
 * Pass A (vectorisable): the seed-free part of `noise2` in noise_numpy.py -- rhombus cell,
 * displacement and `_ext_offsets` (its nested np.where flattened into selects) -- for n points.
 */
ALWAYS_INLINE void chunk_geometry(const double *x, const double *y, Py_ssize_t n,
                                  const NoiseContext *ctx, Scratch *s)
{
    const double overflow[3] = {ctx->overflow_low[0], ctx->overflow_low[1], ctx->overflow_low[2]};
    for (Py_ssize_t j = 0; j < n; j++) {
        double stretch_offset = (x[j] + y[j]) * STRETCH_CONSTANT2;
        double xs = x[j] + stretch_offset;
        double ys = y[j] + stretch_offset;
        double xsb_f = floor(xs);
        double ysb_f = floor(ys);
        double squish_offset = (xsb_f + ysb_f) * SQUISH_CONSTANT2;
        double xins = xs - xsb_f;
        double yins = ys - ysb_f;
        double in_sum = xins + yins;
        double z_lo = 1 - in_sum;
        double z_hi = 2 - in_sum;
        int lower = in_sum <= 1;
        int x_wins = xins > yins;
        int near_lo = (z_lo > xins) | (z_lo > yins);
        int near_hi = (z_hi < xins) | (z_hi < yins);
        double ext_x_lo = (near_lo & !x_wins) ? -1.0 : 1.0;
        double ext_y_lo = (near_lo & x_wins) ? -1.0 : 1.0;
        double ext_x_hi = (near_hi & x_wins) ? 2.0 : 0.0;
        double ext_y_hi = (near_hi & !x_wins) ? 2.0 : 0.0;
        double ext_x = lower ? ext_x_lo : ext_x_hi;
        double ext_y = lower ? ext_y_lo : ext_y_hi;
        double base = lower ? 0.0 : 1.0;
        int32_t low_x = (int32_t)low_byte(xsb_f, overflow);
        int32_t low_y = (int32_t)low_byte(ysb_f, overflow);
        s->key[0][j] = vertex_key(low_x, low_y, 1.0, 0.0);
        s->key[1][j] = vertex_key(low_x, low_y, 0.0, 1.0);
        s->key[2][j] = vertex_key(low_x, low_y, base, base);
        s->key[3][j] = vertex_key(low_x, low_y, ext_x, ext_y);
        s->dx0[j] = x[j] - (xsb_f + squish_offset);
        s->dy0[j] = y[j] - (ysb_f + squish_offset);
        s->ext_x[j] = ext_x;
        s->ext_y[j] = ext_y;
        s->base[j] = base;
    }
}

/* Pass B (scalar look-ups): `perm[(perm[x & 0xFF] + y) & 0xFF] & 0x0E` of every vertex. */
ALWAYS_INLINE void chunk_gradients(Py_ssize_t n, const NoiseContext *ctx, Scratch *s)
{
    for (int v = 0; v < 4; v++) {
        for (Py_ssize_t j = 0; j < n; j++) {
            int32_t key = s->key[v][j];
            s->grad[v][j] = ctx->perm[(ctx->perm[key & 0xFF] + (key >> 8)) & 0xFF] & 0x0E;
        }
    }
}

/*
 * GRADIENTS2[index] * dx + GRADIENTS2[index + 1] * dy for the reference's gradient table
 * (5,2) (2,5) (-5,2) (-2,5) (5,-2) (2,-5) (-5,-2) (-2,-5), index = 2 * pair: the pair is decoded
 * from the bits of index (2 swaps 5/2, 4 negates g1, 8 negates g2) so that the loop vectorises.
 */
ALWAYS_INLINE double decode_dot(unsigned int index, double dx, double dy)
{
    double g1 = (index & 2) ? 2.0 : 5.0;
    double g2 = (index & 2) ? 5.0 : 2.0;
    g1 = (index & 4) ? -g1 : g1;
    g2 = (index & 8) ? -g2 : g2;
    return g1 * dx + g2 * dy;
}

/*
 * `_vertex_term` of noise_numpy.py for vertex (off_x, off_y), a select in place of np.where.
 * off_x/off_y are small integers held exactly as doubles.
 */
ALWAYS_INLINE double vertex_term(double dx0, double dy0, double off_x, double off_y,
                                 unsigned int index)
{
    double squish = (off_x + off_y) * SQUISH_CONSTANT2;
    double dx = (dx0 - off_x) - squish;
    double dy = (dy0 - off_y) - squish;
    double attn = 2 - dx * dx - dy * dy;
    double attn2 = attn * attn;
    double term = attn2 * attn2 * decode_dot(index, dx, dy);
    return attn > 0 ? term : 0.0;
}

/* Pass C (vectorisable): the four contributions in the numpy code's order, / NORM_CONSTANT2. */
ALWAYS_INLINE void chunk_values(Py_ssize_t n, const Scratch *s, double *values)
{
    for (Py_ssize_t j = 0; j < n; j++) {
        double dx0 = s->dx0[j], dy0 = s->dy0[j], base = s->base[j];
        double value = vertex_term(dx0, dy0, 1.0, 0.0, s->grad[0][j]);
        value = value + vertex_term(dx0, dy0, 0.0, 1.0, s->grad[1][j]);
        value = value + vertex_term(dx0, dy0, base, base, s->grad[2][j]);
        value = value + vertex_term(dx0, dy0, s->ext_x[j], s->ext_y[j], s->grad[3][j]);
        values[j] = value / NORM_CONSTANT2;
    }
}

/* OpenSimplex 2-D noise (`noise2` of noise_numpy.py) at (x[j], y[j]) for j < n <= CHUNK. */
ALWAYS_INLINE void noise_chunk(const double *x, const double *y, Py_ssize_t n,
                               const NoiseContext *ctx, Scratch *s, double *values)
{
    chunk_geometry(x, y, n, ctx, s);
    chunk_gradients(n, ctx, s);
    chunk_values(n, s, values);
}

/* `total = total + n * FBM_SCALE * amp` with n = values[j]: the numpy code's accumulation. */
ALWAYS_INLINE void accumulate(double *total, const double *values, Py_ssize_t n, double amp)
{
    for (Py_ssize_t j = 0; j < n; j++) {
        total[j] = total[j] + values[j] * FBM_SCALE * amp;
    }
}

/* `_finish_fbm`: total / norm, optional (out + 1) / 2, then np.clip (NaN passes through). */
ALWAYS_INLINE double finish_fbm(double total, double norm, int to_01)
{
    double out = total / norm;
    double low = -1.0;
    if (to_01) {
        out = (out + 1) / 2;
        low = 0.0;
    }
    if (out != out) {
        return out;
    }
    out = out > low ? out : low;
    return out < 1.0 ? out : 1.0;
}

/* --- buffer handling ------------------------------------------------------------------------ */

/* Format character of a native-order buffer format ("d", "=d", "@d"), or 0 if not native. */
static char native_format(const char *format)
{
    if (format == NULL) {
        return 'B';
    }
    if (format[0] == '@' || format[0] == '=') {
        format++;
    }
#if PY_LITTLE_ENDIAN
    else if (format[0] == '<') {
        format++;
    }
#else
    else if (format[0] == '>' || format[0] == '!') {
        format++;
    }
#endif
    if (format[0] == '\0' || format[1] != '\0') {
        return 0;
    }
    return format[0];
}

/*
 * Get a C-contiguous buffer of `obj` whose item format is one of `accepted` ('d' float64,
 * 'f' float32, 'q' int64); store the format found in *found (may be NULL) and the item count in
 * *count.  Raises TypeError/ValueError naming the argument on failure.
 */
static int get_array(PyObject *obj, const char *name, const char *accepted, int writable,
                     Py_buffer *view, char *found, Py_ssize_t *count)
{
    int flags = PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0);
    if (PyObject_GetBuffer(obj, view, flags) != 0) {
        PyErr_Format(PyExc_TypeError,
                     "%s must be a C-contiguous%s buffer (e.g. numpy array), got %.80s", name,
                     writable ? " writable" : "", Py_TYPE(obj)->tp_name);
        return -1;
    }
    char fmt = native_format(view->format);
    if (fmt == 'l' && sizeof(long) == 8) {
        fmt = 'q';
    }
    size_t expected_size = fmt == 'd' ? 8 : fmt == 'f' ? 4 : fmt == 'q' ? 8 : 0;
    if (fmt == 0 || strchr(accepted, fmt) == NULL || (size_t)view->itemsize != expected_size) {
        PyErr_Format(PyExc_TypeError, "%s has item format '%s'; expected one of '%s' "
                     "(d = float64, f = float32, q = int64, native byte order)",
                     name, view->format ? view->format : "B", accepted);
        PyBuffer_Release(view);
        return -1;
    }
    if (found != NULL) {
        *found = fmt;
    }
    *count = view->len / view->itemsize;
    return 0;
}

/* Fill ctx from the permutation table buffer and the (nan, +big, -big) cast values. */
static int load_context(PyObject *perm_obj, long long cast_nan, long long cast_pos,
                        long long cast_neg, NoiseContext *ctx)
{
    Py_buffer view;
    Py_ssize_t count;
    if (get_array(perm_obj, "perm", "q", 0, &view, NULL, &count) != 0) {
        return -1;
    }
    if (count != 256) {
        PyErr_Format(PyExc_ValueError, "perm must hold 256 int64 values, got %zd", count);
        PyBuffer_Release(&view);
        return -1;
    }
    const int64_t *perm = (const int64_t *)view.buf;
    for (int i = 0; i < 256; i++) {
        if (perm[i] < 0 || perm[i] > 255) {
            PyErr_Format(PyExc_ValueError, "perm[%d] = %lld is outside 0..255", i,
                         (long long)perm[i]);
            PyBuffer_Release(&view);
            return -1;
        }
        ctx->perm[i] = (unsigned char)perm[i];
    }
    PyBuffer_Release(&view);
    ctx->overflow_low[0] = (double)((uint64_t)cast_nan & 0xFF);
    ctx->overflow_low[1] = (double)((uint64_t)cast_pos & 0xFF);
    ctx->overflow_low[2] = (double)((uint64_t)cast_neg & 0xFF);
    return 0;
}

static void release_all(Py_buffer *views, int n)
{
    for (int i = 0; i < n; i++) {
        PyBuffer_Release(&views[i]);
    }
}

/* One array argument: what it must be, and (after get_arrays) its format and item count. */
typedef struct {
    PyObject *obj;
    const char *name, *accepted;
    int writable;
    char format;
    Py_ssize_t count;
} ArrayArg;

/* get_array for each of args[0..n) into views; on failure releases what it got and fails. */
static int get_arrays(ArrayArg *args, Py_buffer *views, int n)
{
    for (int i = 0; i < n; i++) {
        ArrayArg *a = &args[i];
        if (get_array(a->obj, a->name, a->accepted, a->writable, &views[i], &a->format,
                      &a->count) != 0) {
            release_all(views, i);
            return -1;
        }
    }
    return 0;
}

/* Raise ValueError(message), release the n views, return NULL. */
static PyObject *fail(const char *message, Py_buffer *views, int n)
{
    PyErr_SetString(PyExc_ValueError, message);
    release_all(views, n);
    return NULL;
}

/* --- fbm_separable ---------------------------------------------------------------------- */

CPU_CLONES
static void separable_loop(double *out, const double *xs, const double *ys, const double *amps,
                           Py_ssize_t octaves, Py_ssize_t width, Py_ssize_t height, double norm,
                           int to_01, const NoiseContext *ctx)
{
    Scratch scratch;
    double yb[CHUNK], values[CHUNK];
    for (Py_ssize_t i = 0; i < height; i++) {
        for (Py_ssize_t j0 = 0; j0 < width; j0 += CHUNK) {
            Py_ssize_t n = width - j0 < CHUNK ? width - j0 : CHUNK;
            double *total = out + i * width + j0;
            for (Py_ssize_t j = 0; j < n; j++) {
                total[j] = 0.0;
            }
            for (Py_ssize_t k = 0; k < octaves; k++) {
                for (Py_ssize_t j = 0; j < n; j++) {
                    yb[j] = ys[k * height + i];
                }
                noise_chunk(xs + k * width + j0, yb, n, ctx, &scratch, values);
                accumulate(total, values, n, amps[k]);
            }
            for (Py_ssize_t j = 0; j < n; j++) {
                total[j] = finish_fbm(total[j], norm, to_01);
            }
        }
    }
}

PyDoc_STRVAR(fbm_separable_doc,
"fbm_separable(out, xs, ys, amps, perm, cast_values, norm, to_01) -> None\n\n"
"fBm on separable axes into out (float64, H x W = H * W items).  xs: float64 (O, W) and\n"
"ys: float64 (O, H) per-octave coordinates, already scaled; amps: float64 (O,);\n"
"perm: int64 (256,) permutation table; cast_values: numpy's int64 for (NaN, +overflow,\n"
"-overflow) floats; norm: amplitude sum; to_01: map to [0, 1].");

static PyObject *fbm_separable(PyObject *self, PyObject *args)
{
    ArrayArg arr[4] = {{NULL, "out", "d", 1, 0, 0}, {NULL, "xs", "d", 0, 0, 0},
                       {NULL, "ys", "d", 0, 0, 0}, {NULL, "amps", "d", 0, 0, 0}};
    PyObject *perm_obj;
    long long cast_nan, cast_pos, cast_neg;
    double norm;
    int to_01;
    NoiseContext ctx;
    Py_buffer views[4];
    (void)self;
    if (!PyArg_ParseTuple(args, "OOOOO(LLL)dp:fbm_separable", &arr[0].obj, &arr[1].obj,
                          &arr[2].obj, &arr[3].obj, &perm_obj, &cast_nan, &cast_pos, &cast_neg,
                          &norm, &to_01) ||
        load_context(perm_obj, cast_nan, cast_pos, cast_neg, &ctx) != 0 ||
        get_arrays(arr, views, 4) != 0) {
        return NULL;
    }
    Py_ssize_t octaves = arr[3].count;
    if (octaves < 1 || arr[1].count % octaves != 0 || arr[2].count % octaves != 0) {
        return fail("need >= 1 amplitude, and xs/ys sizes divisible by the octave count", views,
                    4);
    }
    Py_ssize_t width = arr[1].count / octaves, height = arr[2].count / octaves;
    if (width != 0 && height > PY_SSIZE_T_MAX / width) {
        return fail("output size overflows", views, 4);
    }
    if (arr[0].count != width * height) {
        return fail("out must hold H * W items for xs (O, W) and ys (O, H)", views, 4);
    }
    Py_BEGIN_ALLOW_THREADS
    separable_loop((double *)views[0].buf, (const double *)views[1].buf,
                   (const double *)views[2].buf, (const double *)views[3].buf, octaves, width,
                   height, norm, to_01, &ctx);
    Py_END_ALLOW_THREADS
    release_all(views, 4);
    Py_RETURN_NONE;
}

/* --- fbm_grid --------------------------------------------------------------------------- */

typedef struct {
    const void *xg, *yg;
    const double *fxs, *fys;
    char x_fmt, y_fmt;
    const double *amps;
    Py_ssize_t octaves, size;
    double norm;
    int to_01;
} GridJob;

/* dst[j] = (double)grid[start + j] * freqs[k]: widened first, multiplied in double. */
ALWAYS_INLINE void scale_chunk(double *dst, const void *grid, const double *freqs, char fmt,
                               Py_ssize_t start, Py_ssize_t n, Py_ssize_t k)
{
    double freq = freqs[k];
    if (fmt == 'f') {
        const float *src = (const float *)grid + start;
        for (Py_ssize_t j = 0; j < n; j++) {
            dst[j] = (double)src[j] * freq;
        }
    } else {
        const double *src = (const double *)grid + start;
        for (Py_ssize_t j = 0; j < n; j++) {
            dst[j] = src[j] * freq;
        }
    }
}

CPU_CLONES
static void grid_loop(double *out, const GridJob *job, const NoiseContext *ctx)
{
    Scratch scratch;
    double xb[CHUNK], yb[CHUNK], values[CHUNK];
    for (Py_ssize_t j0 = 0; j0 < job->size; j0 += CHUNK) {
        Py_ssize_t n = job->size - j0 < CHUNK ? job->size - j0 : CHUNK;
        double *total = out + j0;
        for (Py_ssize_t j = 0; j < n; j++) {
            total[j] = 0.0;
        }
        for (Py_ssize_t k = 0; k < job->octaves; k++) {
            scale_chunk(xb, job->xg, job->fxs, job->x_fmt, j0, n, k);
            scale_chunk(yb, job->yg, job->fys, job->y_fmt, j0, n, k);
            noise_chunk(xb, yb, n, ctx, &scratch, values);
            accumulate(total, values, n, job->amps[k]);
        }
        for (Py_ssize_t j = 0; j < n; j++) {
            total[j] = finish_fbm(total[j], job->norm, job->to_01);
        }
    }
}

PyDoc_STRVAR(fbm_grid_doc,
"fbm_grid(out, x_grid, y_grid, freqs_x, freqs_y, amps, perm, cast_values, norm, to_01)\n\n"
"fBm at N points into out (float64, N items).  x_grid/y_grid: float32 or float64 (N,);\n"
"freqs_x/freqs_y: float64 (O,) per-octave frequencies (each octave's coordinates are widened\n"
"to float64, then multiplied); amps: float64 (O,); the rest as in\n"
"fbm_separable.");

static PyObject *fbm_grid(PyObject *self, PyObject *args)
{
    ArrayArg arr[6] = {{NULL, "out", "d", 1, 0, 0},     {NULL, "x_grid", "fd", 0, 0, 0},
                       {NULL, "y_grid", "fd", 0, 0, 0}, {NULL, "freqs_x", "d", 0, 0, 0},
                       {NULL, "freqs_y", "d", 0, 0, 0}, {NULL, "amps", "d", 0, 0, 0}};
    PyObject *perm_obj;
    long long cast_nan, cast_pos, cast_neg;
    GridJob job;
    NoiseContext ctx;
    Py_buffer views[6];
    (void)self;
    if (!PyArg_ParseTuple(args, "OOOOOOO(LLL)dp:fbm_grid", &arr[0].obj, &arr[1].obj, &arr[2].obj,
                          &arr[3].obj, &arr[4].obj, &arr[5].obj, &perm_obj, &cast_nan, &cast_pos,
                          &cast_neg, &job.norm, &job.to_01) ||
        load_context(perm_obj, cast_nan, cast_pos, cast_neg, &ctx) != 0 ||
        get_arrays(arr, views, 6) != 0) {
        return NULL;
    }
    job.octaves = arr[5].count;
    job.size = arr[0].count;
    if (job.octaves < 1 || arr[3].count != job.octaves || arr[4].count != job.octaves) {
        return fail("need >= 1 amplitude and one frequency per octave in freqs_x/freqs_y", views,
                    6);
    }
    if (arr[1].count != job.size || arr[2].count != job.size) {
        return fail("x_grid, y_grid and out must have the same number of items", views, 6);
    }
    job.xg = views[1].buf;
    job.yg = views[2].buf;
    job.fxs = (const double *)views[3].buf;
    job.fys = (const double *)views[4].buf;
    job.x_fmt = arr[1].format;
    job.y_fmt = arr[2].format;
    job.amps = (const double *)views[5].buf;
    Py_BEGIN_ALLOW_THREADS
    grid_loop((double *)views[0].buf, &job, &ctx);
    Py_END_ALLOW_THREADS
    release_all(views, 6);
    Py_RETURN_NONE;
}

/* --- module ----------------------------------------------------------------------------- */

static PyMethodDef cnoise_methods[] = {
    {"fbm_separable", fbm_separable, METH_VARARGS, fbm_separable_doc},
    {"fbm_grid", fbm_grid, METH_VARARGS, fbm_grid_doc},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef cnoise_module = {
    PyModuleDef_HEAD_INIT, "_cnoise",
    "Compiled OpenSimplex fBm, bit-identical to matloom.engine.kernels.noise_numpy.", -1,
    cnoise_methods, NULL, NULL, NULL, NULL,
};

static int add_float(PyObject *module, const char *name, double value)
{
    PyObject *obj = PyFloat_FromDouble(value);
    if (obj == NULL) {
        return -1;
    }
    if (PyModule_AddObject(module, name, obj) != 0) {
        Py_DECREF(obj);
        return -1;
    }
    return 0;
}

PyMODINIT_FUNC PyInit__cnoise(void)
{
    FBM_SCALE = 2.0 / sqrt(3.0);
    PyObject *module = PyModule_Create(&cnoise_module);
    if (module == NULL) {
        return NULL;
    }
    /* Exposed so the tests can check them against opensimplex.py. */
    if (add_float(module, "STRETCH_CONSTANT2", STRETCH_CONSTANT2) != 0 ||
        add_float(module, "SQUISH_CONSTANT2", SQUISH_CONSTANT2) != 0 ||
        add_float(module, "NORM_CONSTANT2", NORM_CONSTANT2) != 0 ||
        add_float(module, "FBM_SCALE", FBM_SCALE) != 0) {
        Py_DECREF(module);
        return NULL;
    }
    return module;
}

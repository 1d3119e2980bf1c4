/*
 * 3-D convex hull volume and vertices: Quickhull (Barber, Dobkin & Huhdanpaa
 * 1996) for the Stage 3 search of skinrender.design.search.
 *
 * Why: the search builds 42 hulls per sensor triplet (ten prevailing clouds,
 * ten calibration cases and one all-calibration union, for two reflectance
 * sets). scipy.spatial.ConvexHull (Qhull) takes 0.7-1.0 ms for one 1269-chip
 * Munsell cloud on the project's 2-core machines, 0.07 ms of it fixed cost
 * even for 8 points; this kernel takes 0.12-0.16 ms (tests/evaluation/test_hull.py
 * checks it against Qhull; `skinrender bench search` times the search).
 *
 * Scope: only the general case. The kernel answers None, and the caller falls
 * back to Qhull (whose handling of degenerate clouds the project defines), when
 * the cloud is flat or nearly so (volume not above `flat_fraction` of the cube
 * on its bounding box's longest side), when the initial simplex is thin, or when a numerical
 * inconsistency appears (a visible region whose horizon is not one cycle, a
 * new facet of no area or facing inwards: clouds with many coplanar points,
 * such as the impulse sensor's diagonal copies of one cloud, can fold the
 * surface; tests/evaluation/test_hull.py keeps one). Each axis is first
 * centred and scaled to [-1, 1]; there, points within EPS_RELATIVE of a
 * facet's plane count as inside, so a point dropped changes the volume by at
 * most ~1e-12 of it.
 *
 * Steps: within one triplet the ten prevailing clouds, and the ten calibration
 * cases, are the same points moved a little from one to the next. Each hull after
 * the first is built from the previous one's faces (hull_step, below: the old
 * surface on the new coordinates, mended by edge flips and vertex removals, then
 * every other point located and the few outside added as Quickhull adds them),
 * and certified convex and complete before it is used; where it cannot be, the
 * hull is built from scratch. Sensor 9, Munsell set: 3.06 -> 2.25 ms a triplet,
 * about 1 % of steps declined (tests/evaluation/test_hull.py compares every
 * volume with the from-scratch kernel's and Qhull's).
 *
 * Interface (module skinrender.evaluation._hull3d):
 *   hull(points, flat_fraction) -> (volume, vertices) or None
 *     points: C-contiguous float64 buffer of shape (n, 3)
 *     volume: float, in the points' units cubed
 *     vertices: bytes holding int32 vertex indices, ascending
 *   triplet_volumes(clouds, gains, reduce, shared, flat_fraction) -> bytes or None
 *     the whole per-triplet pipeline of search.triplet_volumes_fast in one call,
 *     one workspace reused by all 21 hulls
 *   chunk_volumes(signal, channels, gains, reduce, shared, flat_fraction) -> (bytes, bytes)
 *     the same for many triplets, their clouds gathered here (one call per
 *     chunk of the search: the gathering in numpy took ~50 us per triplet)
 *   steps(enabled=-1) -> (enabled, tried, taken)
 *     whether hulls are stepped, and the steps tried and taken in this process
 *     since the last call (counts are per process; the search runs processes)
 *
 * SPDX-License-Identifier: BSD-3-Clause
 */

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define EPS_RELATIVE 1e-12
#define MAX_DEPTH 20000 /* recursion limit of the horizon search; deeper falls back */
#define FAT_SIMPLEX 0.05 /* an initial simplex from the axis extremes is kept when this fat ([-1, 1] box units) */

typedef struct {
    double n[3];  /* unit outward normal */
    double d;     /* plane: n . x = d */
    double far_dist;
    int v[3];     /* vertices, counter-clockwise seen from outside */
    int nb[3];    /* neighbour across edge v[i] -> v[(i + 1) % 3] */
    int outside;  /* head of the outside-point list, -1 when empty */
    int far;      /* farthest outside point */
    int stamp;    /* iteration of the last visit */
    int fwd;      /* a dead face: a live face near it (hull_step's point witnesses follow it) */
    signed char nbe[3];   /* that edge's index in the neighbour */
    char alive;
    char visible;
} Face;

typedef struct {
    double *x;    /* centred points, n x 3 */
    int n;
    double eps;
    Face *f;
    int nf, cap;
    int *next;    /* outside-list links */
    int *hf, *he; /* horizon: (visible face, edge) in cycle order */
    int nh, hfcap, hecap;
    int *vstamp;  /* per point: iteration that last put it on the horizon */
    int *vis;     /* visible faces of this step */
    int nvis, viscap;
    int iter;     /* never reset: stamps stay valid when the workspace is reused */
    int failed;
    int xcap, nextcap, vstampcap; /* capacities (doubles, ints, ints) */
    double inner[3]; /* a point strictly inside every hull of the steps: the initial simplex's centroid */
    int valid;    /* the faces are the hull of the n points last loaded (hull_step may start from them) */
    int *wit;     /* per point: a face near the point's direction from inner (-1: none) */
    int witcap;
    double *en;   /* per face: its three edge planes through inner (hull_step's point location) */
    int encap;
    int *stack;   /* hull_step's edges to check, (face, edge) pairs */
    int stackcap;
} Hull;

static int grow(void **array, int *cap, int need, size_t size) {
    if (need <= *cap) return 0;
    int cap_new = *cap ? *cap : 16;
    while (cap_new < need) cap_new *= 2;
    void *p = realloc(*array, (size_t)cap_new * size);
    if (!p) return -1;
    *array = p;
    *cap = cap_new;
    return 0;
}

static double distance(const Face *f, const double *p) {
    return f->n[0] * p[0] + f->n[1] * p[1] + f->n[2] * p[2] - f->d;
}

/* Plane of (a, b, c); 0 on success, -1 for a facet of (nearly) no area. */
static int set_plane(Hull *h, Face *f) {
    const double *a = h->x + 3 * f->v[0], *b = h->x + 3 * f->v[1], *c = h->x + 3 * f->v[2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    double length2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    double scale2 = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    /* |u x w| > 1e3 eps |u||w|: the facet's angle is not lost in rounding */
    if (!(length2 > 1e6 * DBL_EPSILON * DBL_EPSILON * scale2)) return -1; /* also 0 and NaN */
    double inverse = 1.0 / sqrt(length2);
    for (int k = 0; k < 3; k++) f->n[k] = n[k] * inverse;
    f->d = (f->n[0] * (a[0] + b[0] + c[0]) + f->n[1] * (a[1] + b[1] + c[1]) + f->n[2] * (a[2] + b[2] + c[2])) / 3.0;
    return 0;
}

static int new_face(Hull *h, int a, int b, int c) {
    if (grow((void **)&h->f, &h->cap, h->nf + 1, sizeof(Face))) return -1;
    Face *f = &h->f[h->nf];
    f->stamp = 0;
    f->visible = 0;
    f->far_dist = 0.0;
    f->v[0] = a;
    f->v[1] = b;
    f->v[2] = c;
    f->outside = -1;
    f->far = -1;
    f->fwd = -1;
    f->alive = 1;
    if (set_plane(h, f)) return -1;
    return h->nf++;
}

static void add_outside(Hull *h, int fi, int p, double dist) {
    Face *f = &h->f[fi];
    h->next[p] = f->outside;
    f->outside = p;
    if (f->far < 0 || dist > f->far_dist) {
        f->far = p;
        f->far_dist = dist;
    }
}

/* Visible faces from `eye`, starting at face fi entered through edge e0 (-1
 * for the first), and the horizon edges in counter-clockwise cycle order
 * (Lloyd's QuickHull3D traversal). */
static void horizon(Hull *h, int fi, int e0, const double *eye, int depth) {
    if (h->failed) return;
    if (depth > MAX_DEPTH) {
        h->failed = 1;
        return;
    }
    Face *f = &h->f[fi];
    f->stamp = h->iter;
    f->visible = 1;
    if (grow((void **)&h->vis, &h->viscap, h->nvis + 1, sizeof(int))) {
        h->failed = 1;
        return;
    }
    h->vis[h->nvis++] = fi;
    int first = e0 < 0 ? 0 : (e0 + 1) % 3;
    int count = e0 < 0 ? 3 : 2;
    for (int k = 0; k < count; k++) {
        int e = (first + k) % 3;
        int g = f->nb[e];
        Face *fg = &h->f[g];
        if (fg->stamp == h->iter && fg->visible) continue;
        if (distance(fg, eye) > h->eps) {
            horizon(h, g, f->nbe[e], eye, depth + 1);
            if (h->failed) return;
        } else {
            fg->stamp = h->iter;
            fg->visible = 0;
            if (grow((void **)&h->hf, &h->hfcap, h->nh + 1, sizeof(int)) ||
                grow((void **)&h->he, &h->hecap, h->nh + 1, sizeof(int))) {
                h->failed = 1;
                return;
            }
            h->hf[h->nh] = fi;
            h->he[h->nh] = e;
            h->nh++;
        }
    }
}

static void link_faces(Hull *h, int f, int e, int g, int ge) {
    h->f[f].nb[e] = g;
    h->f[f].nbe[e] = ge;
    h->f[g].nb[ge] = f;
    h->f[g].nbe[ge] = e;
}

/* One Quickhull step: add the farthest outside point of face fi. */
static int add_point(Hull *h, int fi) {
    int eye = h->f[fi].far;
    const double *pe = h->x + 3 * eye;
    h->iter++;
    h->nvis = 0;
    h->nh = 0;
    horizon(h, fi, -1, pe, 0);
    if (h->failed || h->nh < 3) return -1;
    /* The horizon must be one closed cycle of distinct vertices. */
    for (int k = 0; k < h->nh; k++) {
        const Face *f = &h->f[h->hf[k]], *g = &h->f[h->hf[(k + 1) % h->nh]];
        int start = f->v[h->he[k]];
        if (f->v[(h->he[k] + 1) % 3] != g->v[h->he[(k + 1) % h->nh]] || h->vstamp[start] == h->iter) return -1;
        h->vstamp[start] = h->iter;
    }
    int base = h->nf;
    for (int k = 0; k < h->nh; k++) {
        const Face *f = &h->f[h->hf[k]]; /* read before new_face may move the faces */
        int a = f->v[h->he[k]], b = f->v[(h->he[k] + 1) % 3], out = f->nb[h->he[k]], oute = f->nbe[h->he[k]];
        int g = new_face(h, a, b, eye);
        if (g < 0 || !(distance(&h->f[g], h->inner) < 0.0)) return -1; /* no area, or facing inwards */
        link_faces(h, g, 0, out, oute);
    }
    for (int k = 0; k < h->nh; k++) link_faces(h, base + k, 1, base + (k + 1) % h->nh, 2);
    /* Hand the visible faces' outside points to the new faces: each to a new
     * face it is above, as in Barber et al.'s pseudo-code, trying first the
     * face the previous point went to (the points of one outside set lie close
     * together; looking for the farthest face costs more evaluations than it
     * saves steps: measured). */
    int last = base;
    for (int k = 0; k < h->nvis; k++) {
        Face *f = &h->f[h->vis[k]];
        f->alive = 0;
        int p = f->outside;
        f->outside = -1;
        while (p >= 0) {
            int following = h->next[p];
            if (p != eye) {
                const double *x = h->x + 3 * p;
                int g = last;
                do {
                    double dist = distance(&h->f[g], x);
                    if (dist > h->eps) {
                        add_outside(h, g, p, dist);
                        last = g;
                        break;
                    }
                    if (++g == h->nf) g = base;
                } while (g != last);
            }
            p = following;
        }
    }
    return 0;
}

static double det3(const double *a, const double *b, const double *c, const double *o) {
    double u[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]};
    double v[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
    double w[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

/* The n points into the workspace, each axis centred and scaled to [-1, 1] by its box [lo, hi]; *unit the
 * scales' product. -1 for an axis of no extent. */
static int scale_points(Hull *h, const double *points, int n, const double *lo, const double *hi, double *unit) {
    double centre[3], inverse[3];
    *unit = 1.0;
    for (int k = 0; k < 3; k++) {
        double half = 0.5 * (hi[k] - lo[k]);
        if (!(half > 0.0) || !isfinite(half)) return -1;
        centre[k] = 0.5 * (lo[k] + hi[k]);
        inverse[k] = 1.0 / half;
        *unit *= half;
    }
    double *x = h->x;
    for (int i = 0; i < n; i++) {
        x[3 * i] = (points[3 * i] - centre[0]) * inverse[0];
        x[3 * i + 1] = (points[3 * i + 1] - centre[1]) * inverse[1];
        x[3 * i + 2] = (points[3 * i + 2] - centre[2]) * inverse[2];
    }
    return 0;
}

/* The bounding box of the n points, each axis then centred and scaled to
 * [-1, 1] into the workspace: a diagonal scaling keeps the hull's vertices and
 * multiplies its volume by the scales' product (*unit), and makes one tolerance
 * fit every channel whatever its units. -1 for a non-finite coordinate or an
 * axis of no extent. */
static int load_points(Hull *h, const double *points, int n, double *lo, double *hi, int *arg_lo, int *arg_hi,
                       double *unit) {
    double sum = 0.0; /* not finite if any coordinate is not (or the cloud is absurdly large) */
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = points[k], arg_lo[k] = arg_hi[k] = 0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double value = points[3 * i + k];
            sum += value;
            if (value < lo[k]) lo[k] = value, arg_lo[k] = i;
            if (value > hi[k]) hi[k] = value, arg_hi[k] = i;
        }
    if (!isfinite(sum)) return -1;
    return scale_points(h, points, n, lo, hi, unit);
}

/* 0 and the volume on success; -1 when the caller must fall back to Qhull. */
static int quickhull(Hull *h, const double *points, double flat_fraction, double *volume, char *is_vertex) {
    int n = h->n;
    double *x = h->x;
    if (n < 4) return -1;
    double lo[3], hi[3], unit;
    int arg_lo[3], arg_hi[3];
    if (load_points(h, points, n, lo, hi, arg_lo, arg_hi, &unit)) return -1;
    double side = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    double box = side * side * side; /* the cube on the bounding box's longest side */
    h->eps = EPS_RELATIVE;

    /* Initial simplex: the widest axis extremes, the farthest point from their
     * line, the farthest from their plane; looked for among the six axis
     * extremes first, and among all points when those make a thin simplex. */
    int i0 = 0, i1 = 0;
    double widest = -1.0;
    for (int k = 0; k < 3; k++)
        if (hi[k] - lo[k] > widest) widest = hi[k] - lo[k], i0 = arg_lo[k], i1 = arg_hi[k];
    int extremes[6] = {arg_lo[0], arg_lo[1], arg_lo[2], arg_hi[0], arg_hi[1], arg_hi[2]};
    const double *p0 = x + 3 * i0, *p1 = x + 3 * i1;
    double dir[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    double length = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    int i2 = -1, i3 = -1, base = -1;
    for (int pass = 0; pass < 2 && i3 < 0; pass++) {
        int count = pass ? n : 6;
        double fat = pass ? 1e3 * h->eps : FAT_SIMPLEX; /* pass 1: decline only a truly thin cloud */
        double best = 0.0;
        i2 = -1;
        for (int j = 0; j < count; j++) {
            int i = pass ? j : extremes[j];
            const double *p = x + 3 * i;
            double u[3] = {p[0] - p0[0], p[1] - p0[1], p[2] - p0[2]};
            double c[3] = {u[1] * dir[2] - u[2] * dir[1], u[2] * dir[0] - u[0] * dir[2], u[0] * dir[1] - u[1] * dir[0]};
            double value = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
            if (value > best) best = value, i2 = i;
        }
        if (i2 < 0 || !(sqrt(best) > fat * length)) {
            if (pass) return -1;
            continue;
        }
        h->nf = 0;
        base = new_face(h, i0, i1, i2);
        if (base < 0) {
            if (pass) return -1;
            continue;
        }
        best = 0.0;
        for (int j = 0; j < count; j++) {
            int i = pass ? j : extremes[j];
            double value = fabs(distance(&h->f[base], x + 3 * i));
            if (value > best) best = value, i3 = i;
        }
        if (i3 < 0 || !(best > fat)) {
            if (pass) return -1;
            i3 = -1;
        }
    }
    h->nf = 0;
    int tri[4][3] = {{i0, i1, i2}, {i0, i1, i3}, {i1, i2, i3}, {i2, i0, i3}};
    int other[4] = {i3, i2, i0, i1};
    for (int t = 0; t < 4; t++) {
        int fi = new_face(h, tri[t][0], tri[t][1], tri[t][2]);
        if (fi < 0) return -1;
        if (distance(&h->f[fi], x + 3 * other[t]) > 0.0) {
            Face *f = &h->f[fi];
            int swap = f->v[1];
            f->v[1] = f->v[2];
            f->v[2] = swap;
            if (set_plane(h, f)) return -1;
        }
    }
    for (int a = 0; a < 4; a++)
        for (int e = 0; e < 3; e++)
            for (int b = 0; b < 4; b++)
                for (int g = 0; g < 3; g++)
                    if (a != b && h->f[a].v[e] == h->f[b].v[(g + 1) % 3] && h->f[a].v[(e + 1) % 3] == h->f[b].v[g]) {
                        h->f[a].nb[e] = b;
                        h->f[a].nbe[e] = g;
                    }
    double centre[3];
    for (int k = 0; k < 3; k++) centre[k] = (x[3 * i0 + k] + x[3 * i1 + k] + x[3 * i2 + k] + x[3 * i3 + k]) / 4.0;
    memcpy(h->inner, centre, sizeof(centre));

    for (int i = 0; i < n; i++) {
        if (i == i0 || i == i1 || i == i2 || i == i3) continue;
        int where = -1;
        double far = h->eps;
        for (int t = 0; t < 4; t++) { /* the first face it is above, as add_point does */
            double dist = distance(&h->f[t], x + 3 * i);
            if (dist > far) {
                far = dist, where = t;
                break;
            }
        }
        if (where >= 0) add_outside(h, where, i, far);
    }

    for (int fi = 0; fi < h->nf; fi++) {
        if (!h->f[fi].alive || h->f[fi].outside < 0) continue;
        if (add_point(h, fi)) return -1;
    }

    double total = 0.0;
    memset(is_vertex, 0, (size_t)n);
    for (int fi = 0; fi < h->nf; fi++) {
        const Face *f = &h->f[fi];
        if (!f->alive) continue;
        total += det3(x + 3 * f->v[0], x + 3 * f->v[1], x + 3 * f->v[2], centre);
        for (int k = 0; k < 3; k++) is_vertex[f->v[k]] = 1;
    }
    total *= unit / 6.0;
    if (!(total > flat_fraction * box)) return -1;
    *volume = total;
    return 0;
}

/* After a hull is built: each vertex's witness is a face on it, other points have none yet; the
 * hull may be the start of hull_step. -2 when out of memory. */
static int keep_witnesses(Hull *h) {
    if (grow((void **)&h->wit, &h->witcap, h->n ? h->n : 1, sizeof(int))) return -2;
    for (int i = 0; i < h->n; i++) h->wit[i] = -1;
    for (int fi = 0; fi < h->nf; fi++)
        if (h->f[fi].alive)
            for (int k = 0; k < 3; k++) h->wit[h->f[fi].v[k]] = fi;
    h->valid = 1;
    return 0;
}

/* Load n points (n x 3, any scale) into the reusable workspace and build their
 * hull; is_vertex (n bytes) receives the vertex flags. */
static int hull_points(Hull *h, const double *points, int n, double flat_fraction, double *volume, char *is_vertex) {
    int stamped = h->vstampcap;
    if (grow((void **)&h->x, &h->xcap, 3 * (n ? n : 1), sizeof(double)) ||
        grow((void **)&h->next, &h->nextcap, n ? n : 1, sizeof(int)) ||
        grow((void **)&h->vstamp, &h->vstampcap, n ? n : 1, sizeof(int)))
        return -2;
    if (h->vstampcap > stamped) memset(h->vstamp + stamped, 0, sizeof(int) * (size_t)(h->vstampcap - stamped));
    h->n = n;
    h->nf = 0;
    h->failed = 0;
    h->valid = 0;
    int status = quickhull(h, points, flat_fraction, volume, is_vertex);
    if (status == 0) status = keep_witnesses(h);
    return status;
}

/* ------------------------------------------------------------------------- *
 * hull_step: the hull of the same n points at new coordinates, from the faces of
 * their previous hull (the search's clouds change little from one illuminant, or
 * one calibration, to the next). The previous triangulation is put on the new
 * coordinates and mended: a reflex edge is flipped, a vertex of degree three
 * under its neighbours' plane is removed; then every other point is located on
 * the surface (the face its direction from an inner point crosses, found by a
 * walk from the face that held it before) and the points above their face are
 * added as Quickhull adds them. What comes out is certified, not assumed: every
 * edge convex, every face facing away from the inner point, a ray from that
 * point crossing exactly one face (so the surface wraps it once: with the
 * faces all facing away and the edges convex, a convex polytope), every point
 * not a vertex under the plane of the face its direction crosses (so inside
 * it). Anything else answers -1 and the caller builds the hull from scratch.
 * ------------------------------------------------------------------------- */

#define WALK_STEPS_MAX 64 /* a longer walk gives way to a search over every face */
#define CONE_SLACK 1e-12 /* the search's face may miss y's direction by this much (relative), no more */
#define FORWARDS_MAX 64 /* a dead face's chain of successors is followed this far at most */
static const double RAY[3] = {0.5773502691896258, 0.5812381937190965, 0.5734623443633283}; /* a direction, no axis */
#define RAY_GRAZE2 1e-18 /* a face's edge plane this close (1e-9, relative) to the ray: the count is in doubt */

static int index_of(const Face *f, int v) { return f->v[0] == v ? 0 : f->v[1] == v ? 1 : f->v[2] == v ? 2 : -1; }

/* Faces around vertex a from face fi (-1: the fan does not close); *has_d: whether d is one of a's neighbours. */
static int fan(const Hull *h, int fi, int a, int d, int *has_d) {
    int count = 0, f = fi;
    *has_d = 0;
    do {
        const Face *F = &h->f[f];
        int k = index_of(F, a);
        if (k < 0 || !F->alive) return -1;
        if (F->v[(k + 1) % 3] == d || F->v[(k + 2) % 3] == d) *has_d = 1;
        f = F->nb[(k + 2) % 3];
        if (++count > h->nf) return -1;
    } while (f != fi);
    return count;
}

static int push(Hull *h, int *ns, int fi, int e) {
    if (grow((void **)&h->stack, &h->stackcap, 2 * (*ns + 1), sizeof(int))) return -2;
    h->stack[2 * *ns] = fi;
    h->stack[2 * *ns + 1] = e;
    (*ns)++;
    return 0;
}

/* A face made or changed by the repair: its plane, facing away from the inner point. */
static int replane(Hull *h, Face *f) { return set_plane(h, f) || !(distance(f, h->inner) < 0.0) ? -1 : 0; }

/* The orientation of (a, b, c) seen from o: positive when the triangle faces away from o. */
static double orient(const Hull *h, int a, int b, int c, const double *o) {
    return det3(h->x + 3 * a, h->x + 3 * b, h->x + 3 * c, o);
}

/* Flip edge e of face fi (a -> b, far vertex c) shared with face gi (b -> a, far vertex d):
 * the faces become (a, d, c) and (d, b, c). 1 (nothing done) where either would not face away
 * from the inner point: the edge waits for other repairs. */
static int flip(Hull *h, int fi, int e, int *ns) {
    Face *f = &h->f[fi];
    int gi = f->nb[e], ge = f->nbe[e];
    Face *g = &h->f[gi];
    int a = f->v[e], b = f->v[(e + 1) % 3], c = f->v[(e + 2) % 3], d = g->v[(ge + 2) % 3];
    if (!(orient(h, a, d, c, h->inner) > 0.0) || !(orient(h, d, b, c, h->inner) > 0.0)) return 1;
    int fbc = f->nb[(e + 1) % 3], fbce = f->nbe[(e + 1) % 3], fca = f->nb[(e + 2) % 3], fcae = f->nbe[(e + 2) % 3];
    int gad = g->nb[(ge + 1) % 3], gade = g->nbe[(ge + 1) % 3], gdb = g->nb[(ge + 2) % 3], gdbe = g->nbe[(ge + 2) % 3];
    if (fbc == gi || fca == gi || gad == fi || gdb == fi) return -1;
    f->v[0] = a, f->v[1] = d, f->v[2] = c;
    g->v[0] = d, g->v[1] = b, g->v[2] = c;
    if (replane(h, f) || replane(h, g)) return -1;
    link_faces(h, fi, 0, gad, gade);
    link_faces(h, fi, 2, fca, fcae);
    link_faces(h, gi, 0, gdb, gdbe);
    link_faces(h, gi, 1, fbc, fbce);
    link_faces(h, fi, 1, gi, 2);
    int status = 0;
    for (int k = 0; k < 3 && !status; k++) status = push(h, ns, fi, k) || push(h, ns, gi, k);
    return status ? -2 : 0;
}

/* Remove vertex a of degree three (faces fi and the two next around it): one face on its three
 * neighbours takes their place. */
static int remove_vertex(Hull *h, int fi, int a, int *ns) {
    int faces[3], ring[3], out[3], oute[3], f = fi;
    for (int t = 0; t < 3; t++) {
        const Face *F = &h->f[f];
        int k = index_of(F, a);
        faces[t] = f;
        ring[t] = F->v[(k + 1) % 3];
        out[t] = F->nb[(k + 1) % 3];
        oute[t] = F->nbe[(k + 1) % 3];
        f = F->nb[(k + 2) % 3];
    }
    if (f != fi) return -1;
    for (int t = 0; t < 3; t++)
        if (out[t] == faces[0] || out[t] == faces[1] || out[t] == faces[2]) return -1; /* a tetrahedron */
    Face *F = &h->f[faces[0]];
    memcpy(F->v, ring, sizeof(ring));
    if (replane(h, F)) return -1;
    for (int t = 1; t < 3; t++) {
        h->f[faces[t]].alive = 0;
        h->f[faces[t]].fwd = faces[0];
    }
    for (int t = 0; t < 3; t++) link_faces(h, faces[0], t, out[t], oute[t]);
    h->wit[a] = faces[0];
    int status = 0;
    for (int k = 0; k < 3 && !status; k++) status = push(h, ns, faces[0], k);
    return status ? -2 : 0;
}

/* Faces turned towards the inner point by the new coordinates (folds of the old surface): each is
 * flipped with a neighbour where both new faces face away from it. -1 where one is left. */
static int unfold(Hull *h) {
    for (int fi = 0; fi < h->nf; fi++) {
        Face *f = &h->f[fi];
        if (!f->alive || distance(f, h->inner) < 0.0) continue;
        int mended = 0;
        for (int e = 0; e < 3 && !mended; e++) {
            const Face *g = &h->f[f->nb[e]];
            int c = f->v[(e + 2) % 3], d = g->v[(f->nbe[e] + 2) % 3], joined;
            if (c == d || fan(h, fi, c, d, &joined) < 0 || joined) continue;
            int ns = 0, status = flip(h, fi, e, &ns);
            if (status < 0) return status;
            mended = status == 0;
        }
        if (!mended) return -1;
    }
    return 0;
}

/* Whether edge e of face fi bends inwards: the neighbour's far vertex above fi's plane. */
static int reflex(const Hull *h, int fi, int e) {
    const Face *f = &h->f[fi], *g = &h->f[f->nb[e]];
    return distance(f, h->x + 3 * g->v[(f->nbe[e] + 2) % 3]) > h->eps;
}

/* Mend every reflex edge; 0 when none is left, -1 when the mending is stuck (-2 out of memory). The
 * stack holds the edges to look at: the reflex ones at first, then those of every face changed; an
 * edge whose flip would turn a face towards the inner point waits for the others. */
static int mend(Hull *h) {
    int ns = 0, budget = 16 * h->nf + 64;
    for (int fi = 0; fi < h->nf; fi++)
        if (h->f[fi].alive)
            for (int e = 0; e < 3; e++)
                if (h->f[fi].nb[e] > fi && reflex(h, fi, e) && push(h, &ns, fi, e)) return -2;
    int waiting = 0;
    while (ns > 0) {
        int done = 0;
        while (ns > waiting) {
            ns--;
            int fi = h->stack[2 * ns], e = h->stack[2 * ns + 1];
            if (!h->f[fi].alive || !reflex(h, fi, e)) continue;
            if (--budget < 0) return -1;
            const Face *f = &h->f[fi];
            const Face *g = &h->f[f->nb[e]];
            int a = f->v[e], b = f->v[(e + 1) % 3], c = f->v[(e + 2) % 3], d = g->v[(f->nbe[e] + 2) % 3];
            int joined, unused;
            if (c == d || fan(h, fi, c, d, &joined) < 0) return -1;
            int status;
            if (fan(h, fi, a, -1, &unused) == 3) {
                status = remove_vertex(h, fi, a, &ns);
            } else if (fan(h, fi, b, -1, &unused) == 3) {
                status = remove_vertex(h, fi, b, &ns);
            } else if (!joined) {
                status = flip(h, fi, e, &ns);
            } else {
                status = 1;
            }
            if (status == 1) { /* to the bottom of the stack, below the edges still to look at */
                if (push(h, &ns, 0, 0)) return -2;
                memmove(h->stack + 2, h->stack, sizeof(int) * 2 * (size_t)(ns - 1));
                h->stack[0] = fi, h->stack[1] = e;
                waiting++;
                continue;
            }
            if (status) return status;
            done++;
        }
        if (!done) {
            for (int k = 0; k < ns; k++)
                if (h->f[h->stack[2 * k]].alive && reflex(h, h->stack[2 * k], h->stack[2 * k + 1])) return -1;
            return 0;
        }
        waiting = 0; /* the waiting edges are looked at again after the others' repairs */
    }
    return 0;
}

/* The face whose cone from o holds y = x - o: a walk from `start` across the edge plane y is most
 * behind, then (rarely) a search over every face for the cone y is least outside; -1 where even that
 * one misses y by more than CONE_SLACK. */
static inline int locate(Hull *h, int start, const double *y) {
    int f = start;
    for (int s = 0; s < WALK_STEPS_MAX; s++) {
        const double *e = h->en + 9 * (size_t)f;
        double t0 = e[0] * y[0] + e[1] * y[1] + e[2] * y[2], t1 = e[3] * y[0] + e[4] * y[1] + e[5] * y[2],
               t2 = e[6] * y[0] + e[7] * y[1] + e[8] * y[2];
        if (t0 >= 0.0 && t1 >= 0.0 && t2 >= 0.0) return f;
        f = h->f[f].nb[t0 <= t1 ? (t0 <= t2 ? 0 : 2) : (t1 <= t2 ? 1 : 2)];
    }
    int best = -1;
    double best_worst = -INFINITY; /* the edge planes' signed distances of y's direction, unit vectors */
    for (int fi = 0; fi < h->nf; fi++) {
        if (!h->f[fi].alive) continue;
        const double *e = h->en + 9 * (size_t)fi;
        double worst = INFINITY;
        for (int j = 0; j < 3; j++) {
            double length = sqrt(e[3 * j] * e[3 * j] + e[3 * j + 1] * e[3 * j + 1] + e[3 * j + 2] * e[3 * j + 2]);
            worst = fmin(worst, (e[3 * j] * y[0] + e[3 * j + 1] * y[1] + e[3 * j + 2] * y[2]) / length);
        }
        if (worst > best_worst) best_worst = worst, best = fi;
    }
    return best_worst >= -CONE_SLACK * sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) ? best : -1;
}

/* load_points without the extremes' indices (hull_step needs none): the box, each axis centred and
 * scaled to [-1, 1]; -1 for a non-finite coordinate or an axis of no extent. */
static int load_box(Hull *h, const double *points, int n, double *lo, double *hi, double *unit) {
    double l0 = points[0], l1 = points[1], l2 = points[2], h0 = l0, h1 = l1, h2 = l2, sum = 0.0;
    for (int i = 0; i < n; i++) {
        double a = points[3 * i], b = points[3 * i + 1], c = points[3 * i + 2];
        sum += a + b + c;
        l0 = a < l0 ? a : l0, l1 = b < l1 ? b : l1, l2 = c < l2 ? c : l2;
        h0 = a > h0 ? a : h0, h1 = b > h1 ? b : h1, h2 = c > h2 ? c : h2;
    }
    if (!isfinite(sum)) return -1;
    lo[0] = l0, lo[1] = l1, lo[2] = l2, hi[0] = h0, hi[1] = h1, hi[2] = h2;
    return scale_points(h, points, n, lo, hi, unit);
}

/* Only the live faces kept, in order, their neighbours and the points' witnesses renumbered
 * (Quickhull leaves more dead faces than live ones); -2 when out of memory. */
static int compact(Hull *h) {
    if (grow((void **)&h->stack, &h->stackcap, h->nf ? h->nf : 1, sizeof(int))) return -2;
    int *map = h->stack, m = 0;
    for (int fi = 0; fi < h->nf; fi++) map[fi] = h->f[fi].alive ? m++ : -1;
    for (int fi = 0; fi < h->nf; fi++) {
        if (h->f[fi].alive) continue;
        int t = h->f[fi].fwd;
        for (int k = 0; k < 64 && t >= 0 && !h->f[t].alive; k++) t = h->f[t].fwd;
        h->f[fi].fwd = t >= 0 && h->f[t].alive ? t : -1;
    }
    for (int i = 0; i < h->n; i++) {
        int w = h->wit[i];
        if (w >= 0 && !h->f[w].alive) w = h->f[w].fwd;
        h->wit[i] = w >= 0 ? map[w] : -1;
    }
    for (int fi = 0; fi < h->nf; fi++) {
        if (map[fi] < 0) continue;
        Face *f = &h->f[map[fi]];
        if (map[fi] != fi) *f = h->f[fi];
        for (int k = 0; k < 3; k++) f->nb[k] = map[f->nb[k]];
    }
    h->nf = m;
    return 0;
}

/* The hull of the previous hull's n points at new coordinates (see above); 0 and the volume, or -1:
 * build it from scratch (-2 out of memory). */
static int hull_step(Hull *h, const double *points, double flat_fraction, double *volume, char *is_vertex) {
    int n = h->n;
    if (!h->valid || n < 4) return -1;
    h->valid = 0;
    h->failed = 0;
    double lo[3], hi[3], unit;
    if (load_box(h, points, n, lo, hi, &unit)) return -1;
    int live = 0;
    for (int fi = 0; fi < h->nf; fi++) live += h->f[fi].alive;
    if (4 * live < 3 * h->nf && compact(h)) return -2;
    double side = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    h->eps = EPS_RELATIVE;
    /* the inner point: the previous vertices' centroid, inside the new hull as they are among its points */
    double o[3] = {0.0, 0.0, 0.0};
    int count = 0;
    memset(is_vertex, 0, (size_t)n);
    for (int fi = 0; fi < h->nf; fi++)
        if (h->f[fi].alive)
            for (int k = 0; k < 3; k++) is_vertex[h->f[fi].v[k]] = 1;
    for (int i = 0; i < n; i++)
        if (is_vertex[i]) {
            for (int k = 0; k < 3; k++) o[k] += h->x[3 * i + k];
            count++;
        }
    for (int k = 0; k < 3; k++) o[k] /= count;
    memcpy(h->inner, o, sizeof(o));
    int folded = 0;
    for (int fi = 0; fi < h->nf; fi++) {
        Face *f = &h->f[fi];
        if (!f->alive) continue;
        f->outside = -1, f->far = -1, f->far_dist = 0.0, f->visible = 0;
        if (set_plane(h, f)) return -1;
        folded += !(distance(f, h->inner) < 0.0);
    }
    if (folded && unfold(h)) return -1;
    int status = mend(h);
    if (status) return status;
    /* every face's three edge planes through o, for the point location and the wrapping count */
    if (grow((void **)&h->en, &h->encap, 9 * h->nf, sizeof(double))) return -2;
    memset(is_vertex, 0, (size_t)n);
    int crossed = 0, grazed = 0;
    for (int fi = 0; fi < h->nf; fi++) {
        const Face *f = &h->f[fi];
        if (!f->alive) continue;
        double r[3][3];
        for (int k = 0; k < 3; k++) {
            is_vertex[f->v[k]] = 1;
            for (int j = 0; j < 3; j++) r[k][j] = h->x[3 * f->v[k] + j] - o[j];
        }
        double *e = h->en + 9 * (size_t)fi;
        for (int k = 0; k < 3; k++) {
            const double *u = r[k], *w = r[(k + 1) % 3];
            e[3 * k] = u[1] * w[2] - u[2] * w[1];
            e[3 * k + 1] = u[2] * w[0] - u[0] * w[2];
            e[3 * k + 2] = u[0] * w[1] - u[1] * w[0];
        }
        /* does the ray from o along RAY cross this face (all three edge planes in front)? */
        double t0 = e[0] * RAY[0] + e[1] * RAY[1] + e[2] * RAY[2], t1 = e[3] * RAY[0] + e[4] * RAY[1] + e[5] * RAY[2],
               t2 = e[6] * RAY[0] + e[7] * RAY[1] + e[8] * RAY[2];
        if (t0 > 0.0 && t1 > 0.0 && t2 > 0.0) crossed++;
        grazed |= t0 * t0 <= RAY_GRAZE2 * (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) ||
                  t1 * t1 <= RAY_GRAZE2 * (e[3] * e[3] + e[4] * e[4] + e[5] * e[5]) ||
                  t2 * t2 <= RAY_GRAZE2 * (e[6] * e[6] + e[7] * e[7] + e[8] * e[8]);
    }
    /* The faces all face away from o, so the surface wraps o as many times as a ray crosses it: once
     * (a ray along an edge could miscount, so a grazing ray declines the step). */
    if (crossed != 1 || grazed) return -1;
    /* locate every point that is not a vertex; those above their face are Quickhull's outside points */
    int last = -1;
    for (int fi = 0; fi < h->nf && last < 0; fi++)
        if (h->f[fi].alive) last = fi;
    for (int i = 0; i < n; i++) {
        if (is_vertex[i]) continue;
        int start = h->wit[i];
        for (int k = 0; k < FORWARDS_MAX && start >= 0 && !h->f[start].alive; k++) start = h->f[start].fwd;
        if (start >= 0 && !h->f[start].alive) start = -1;
        if (start < 0) start = last;
        const double *x = h->x + 3 * i;
        double y[3] = {x[0] - o[0], x[1] - o[1], x[2] - o[2]};
        int f = locate(h, start, y);
        if (f < 0) return -1;
        double dist = distance(&h->f[f], x);
        if (dist > h->eps) add_outside(h, f, i, dist);
        h->wit[i] = f;
        last = f;
    }
    for (int fi = 0; fi < h->nf; fi++) {
        if (!h->f[fi].alive || h->f[fi].outside < 0) continue;
        int base = h->nf;
        if (add_point(h, fi)) return -1;
        for (int k = 0; k < h->nvis; k++) h->f[h->vis[k]].fwd = base;
    }
    double total = 0.0;
    memset(is_vertex, 0, (size_t)n);
    for (int fi = 0; fi < h->nf; fi++) {
        const Face *f = &h->f[fi];
        if (!f->alive) continue;
        total += det3(h->x + 3 * f->v[0], h->x + 3 * f->v[1], h->x + 3 * f->v[2], o);
        for (int k = 0; k < 3; k++) {
            is_vertex[f->v[k]] = 1;
            h->wit[f->v[k]] = fi;
        }
    }
    total *= unit / 6.0;
    if (!(total > flat_fraction * side * side * side)) return -1;
    *volume = total;
    h->valid = 1;
    return 0;
}

static int STEPS = 1;              /* hull_next may step (steps() turns it off, for tests and timings) */
static long STEPS_TRIED = 0, STEPS_TAKEN = 0; /* since the last steps() call, in this process */

/* The hull of n points: from the workspace's previous hull of the same points (hull_step) where `follow`,
 * from scratch otherwise or where the step declines. */
static int hull_next(Hull *h, const double *points, int n, int follow, double flat, double *volume, char *is_vertex) {
    if (follow && STEPS && h->valid && h->n == n) {
        STEPS_TRIED++;
        int status = hull_step(h, points, flat, volume, is_vertex);
        if (status != -1) {
            STEPS_TAKEN += status == 0;
            return status;
        }
    }
    return hull_points(h, points, n, flat, volume, is_vertex);
}

static void release(Hull *h) {
    free(h->x);
    free(h->next);
    free(h->vstamp);
    free(h->f);
    free(h->hf);
    free(h->he);
    free(h->vis);
    free(h->wit);
    free(h->en);
    free(h->stack);
}

/* A C-contiguous float64 array of `ndim` dimensions whose last is 3; 0 or -1 with ValueError set. */
static int get_points(PyObject *object, int ndim, const char *name, Py_buffer *view) {
    if (PyObject_GetBuffer(object, view, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | PyBUF_ND)) {
        PyErr_Clear();
        view->obj = NULL;
    } else if (view->ndim == ndim && view->shape[ndim - 1] == 3 && view->itemsize == 8 && view->format &&
               !strcmp(view->format, "d") && view->len / 8 < 300000000) {
        return 0;
    } else {
        PyBuffer_Release(view);
    }
    PyErr_Format(PyExc_ValueError, "%s must be a C-contiguous float64 array of shape (%s3)", name,
                 ndim == 2 ? "n, " : "P, n, ");
    return -1;
}

static PyObject *result_or_none(int status, PyObject *(*build)(void *), void *data) {
    if (status == -2) return PyErr_NoMemory();
    if (status != 0) return Py_NewRef(Py_None);
    return build(data);
}

typedef struct {
    double volume;
    const char *is_vertex;
    int n;
} HullAnswer;

static PyObject *build_hull(void *data) {
    HullAnswer *a = data;
    int vertices = 0;
    for (int i = 0; i < a->n; i++) vertices += a->is_vertex[i];
    PyObject *bytes = PyBytes_FromStringAndSize(NULL, (Py_ssize_t)vertices * (Py_ssize_t)sizeof(int));
    if (!bytes) return NULL;
    int *out = (int *)PyBytes_AS_STRING(bytes);
    for (int i = 0, j = 0; i < a->n; i++)
        if (a->is_vertex[i]) out[j++] = i;
    return Py_BuildValue("(dN)", a->volume, bytes);
}

static PyObject *hull(PyObject *self, PyObject *args) {
    PyObject *object;
    double flat_fraction;
    (void)self;
    if (!PyArg_ParseTuple(args, "Od", &object, &flat_fraction)) return NULL;
    Py_buffer view;
    if (get_points(object, 2, "points", &view)) return NULL;
    int n = (int)view.shape[0];
    Hull h;
    memset(&h, 0, sizeof(h));
    char *is_vertex = malloc((size_t)(n ? n : 1));
    HullAnswer answer = {0.0, is_vertex, n};
    int status = -2;
    if (is_vertex) {
        Py_BEGIN_ALLOW_THREADS status = hull_points(&h, view.buf, n, flat_fraction, &answer.volume, is_vertex);
        Py_END_ALLOW_THREADS
    }
    PyBuffer_Release(&view);
    PyObject *result = result_or_none(status, build_hull, &answer);
    free(is_vertex);
    release(&h);
    return result;
}

/* The volumes of one sensor triplet (see triplet_volumes_fast in search.py):
 * the prevailing clouds reduced to their vertices, the Q calibration cases
 * from the scaled vertices, the all-calibration hull from the cases' vertices. */
static int triplet(Hull *h, const double *clouds, const double *gains, int P, int N, int Q, int reduce, int shared,
                   double flat, double *volumes) {
    size_t most = (size_t)P * (size_t)N;
    double *reduced = malloc(sizeof(double) * 3 * (most ? most : 1));
    double *points = malloc(sizeof(double) * 3 * (most ? most : 1));
    double *all = NULL; /* the cases' vertices: at most Q times the reduced count */
    char *all_vertex = NULL;
    int *owner = malloc(sizeof(int) * (most ? most : 1));
    char *is_vertex = malloc(most ? most : 1);
    int status = -2;
    if (!reduced || !points || !owner || !is_vertex) goto done;
    int count = 0;
    for (int p = 0; p < P; p++) {
        const double *cloud = clouds + (size_t)p * N * 3;
        if (reduce && (!shared || p == 0)) {
            double volume;
            status = hull_next(h, cloud, N, p > 0, flat, &volume, is_vertex);
            if (status) goto done;
        }
        for (int i = 0; i < N; i++)
            if (!reduce || is_vertex[i]) {
                memcpy(reduced + 3 * (size_t)count, cloud + 3 * (size_t)i, 3 * sizeof(double));
                owner[count++] = p;
            }
    }
    size_t total = 0;
    all = malloc(sizeof(double) * 3 * (size_t)(count ? count : 1) * (size_t)Q);
    if (!all) {
        status = -2;
        goto done;
    }
    for (int q = 0; q < Q; q++) {
        for (int i = 0; i < count; i++) {
            const double *gain = gains + 3 * ((size_t)owner[i] * Q + q);
            for (int k = 0; k < 3; k++) points[3 * i + k] = reduced[3 * i + k] * gain[k];
        }
        status = hull_next(h, points, count, q > 0, flat, &volumes[q], is_vertex);
        if (status) goto done;
        for (int i = 0; i < count; i++)
            if (is_vertex[i]) memcpy(all + 3 * total++, points + 3 * i, 3 * sizeof(double));
    }
    if (total > 2000000000u) {
        status = -1;
        goto done;
    }
    all_vertex = malloc(total ? total : 1);
    if (!all_vertex) {
        status = -2;
        goto done;
    }
    status = hull_points(h, all, (int)total, flat, &volumes[Q], all_vertex);
done:
    free(all_vertex);
    free(reduced);
    free(points);
    free(all);
    free(owner);
    free(is_vertex);
    return status;
}

static PyObject *build_volumes(void *data) {
    Py_buffer *volumes = data;
    return PyBytes_FromStringAndSize(volumes->buf, volumes->len);
}

static PyObject *triplet_volumes(PyObject *self, PyObject *args) {
    PyObject *clouds_object, *gains_object;
    int reduce, shared;
    double flat_fraction;
    (void)self;
    if (!PyArg_ParseTuple(args, "OOppd", &clouds_object, &gains_object, &reduce, &shared, &flat_fraction)) return NULL;
    Py_buffer clouds, gains;
    if (get_points(clouds_object, 3, "clouds", &clouds)) return NULL;
    if (get_points(gains_object, 3, "gains", &gains)) {
        PyBuffer_Release(&clouds);
        return NULL;
    }
    int P = (int)clouds.shape[0], N = (int)clouds.shape[1], Q = (int)gains.shape[1];
    if (gains.shape[0] != P || P < 1 || Q < 1) {
        PyBuffer_Release(&clouds);
        PyBuffer_Release(&gains);
        PyErr_SetString(PyExc_ValueError, "gains must have shape (P, Q, 3) for clouds of shape (P, n, 3)");
        return NULL;
    }
    double *volumes = malloc(sizeof(double) * (size_t)(Q + 1));
    int status = -2;
    Hull h;
    memset(&h, 0, sizeof(h));
    if (volumes) {
        Py_BEGIN_ALLOW_THREADS status =
            triplet(&h, clouds.buf, gains.buf, P, N, Q, reduce, shared, flat_fraction, volumes);
        Py_END_ALLOW_THREADS
    }
    PyBuffer_Release(&clouds);
    PyBuffer_Release(&gains);
    release(&h);
    Py_buffer out = {.buf = volumes, .len = (Py_ssize_t)sizeof(double) * (Q + 1)};
    PyObject *result = result_or_none(status, build_volumes, &out);
    free(volumes);
    return result;
}

/* A C-contiguous array of `ndim` dimensions of float64 (integer: int64); 0, or -1 with ValueError set. */
static int get_array(PyObject *object, int ndim, int integer, const char *name, const char *shape, Py_buffer *view) {
    if (PyObject_GetBuffer(object, view, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | PyBUF_ND)) {
        PyErr_Clear();
        view->obj = NULL;
    } else if (view->ndim == ndim && view->itemsize == 8 && view->format &&
               (integer ? (!strcmp(view->format, "l") || !strcmp(view->format, "q")) : !strcmp(view->format, "d")) &&
               view->len / 8 < 2000000000) {
        return 0;
    } else {
        PyBuffer_Release(view);
    }
    PyErr_Format(PyExc_ValueError, "%s must be a C-contiguous %s array of shape %s", name, integer ? "int64" : "float64",
                 shape);
    return -1;
}

/* triplet() for T triplets gathered here from the single-sensor responses
 * (signal[j, p, i]: position j, illuminant p, reflectance i); declined[t] = 1
 * where a hull was declined (that row of volumes is left NaN). */
static int chunk(const double *signal, int P, int N, const long long *channels, int T, const double *gains,
                 int Q, int reduce, int shared, double flat, double *volumes, char *declined) {
    double *clouds = malloc(sizeof(double) * 3 * (size_t)P * (size_t)(N ? N : 1));
    if (!clouds) return -2;
    Hull h;
    memset(&h, 0, sizeof(h));
    int status = 0;
    for (int t = 0; t < T && status != -2; t++) {
        const long long *c = channels + 3 * (size_t)t;
        for (int p = 0; p < P; p++)
            for (int k = 0; k < 3; k++) {
                const double *from = signal + ((size_t)c[k] * P + p) * N;
                double *to = clouds + (size_t)p * N * 3 + k;
                for (int i = 0; i < N; i++) to[3 * i] = from[i];
            }
        double *row = volumes + (size_t)t * (Q + 1);
        status = triplet(&h, clouds, gains + (size_t)t * P * Q * 3, P, N, Q, reduce, shared, flat, row);
        declined[t] = status != 0;
        if (status) {
            for (int q = 0; q <= Q; q++) row[q] = NAN;
        }
    }
    release(&h);
    free(clouds);
    return status == -2 ? -2 : 0;
}

static PyObject *build_chunk(void *data) {
    Py_buffer *parts = data; /* volumes, declined */
    return Py_BuildValue("(y#y#)", (const char *)parts[0].buf, parts[0].len, (const char *)parts[1].buf, parts[1].len);
}

static PyObject *chunk_volumes(PyObject *self, PyObject *args) {
    PyObject *signal_object, *channels_object, *gains_object;
    int reduce, shared;
    double flat_fraction;
    (void)self;
    if (!PyArg_ParseTuple(args, "OOOppd", &signal_object, &channels_object, &gains_object, &reduce, &shared,
                          &flat_fraction))
        return NULL;
    Py_buffer signal, channels, gains;
    if (get_array(signal_object, 3, 0, "signal", "(J, P, n)", &signal)) return NULL;
    if (get_array(channels_object, 2, 1, "channels", "(T, 3)", &channels)) {
        PyBuffer_Release(&signal);
        return NULL;
    }
    if (get_array(gains_object, 4, 0, "gains", "(T, P, Q, 3)", &gains)) {
        PyBuffer_Release(&signal);
        PyBuffer_Release(&channels);
        return NULL;
    }
    int J = (int)signal.shape[0], P = (int)signal.shape[1], N = (int)signal.shape[2];
    int T = (int)channels.shape[0], Q = (int)gains.shape[2];
    const char *problem = NULL;
    if (channels.shape[1] != 3 || gains.shape[0] != T || gains.shape[1] != P || gains.shape[3] != 3 || P < 1 || Q < 1)
        problem = "gains must have shape (T, P, Q, 3) for signal (J, P, n) and channels (T, 3)";
    const long long *c = channels.buf;
    for (Py_ssize_t k = 0; !problem && k < 3 * (Py_ssize_t)T; k++)
        if (c[k] < 0 || c[k] >= J) problem = "channels must be positions in [0, J)";
    double *volumes = problem ? NULL : malloc(sizeof(double) * (size_t)(T ? T : 1) * (size_t)(Q + 1));
    char *declined = problem ? NULL : malloc((size_t)(T ? T : 1));
    int status = -2;
    if (volumes && declined) {
        Py_BEGIN_ALLOW_THREADS status = chunk(signal.buf, P, N, c, T, gains.buf, Q, reduce, shared, flat_fraction,
                                              volumes, declined);
        Py_END_ALLOW_THREADS
    }
    PyBuffer_Release(&signal);
    PyBuffer_Release(&channels);
    PyBuffer_Release(&gains);
    PyObject *result;
    if (problem) {
        PyErr_SetString(PyExc_ValueError, problem);
        result = NULL;
    } else {
        Py_buffer parts[2] = {{.buf = volumes, .len = (Py_ssize_t)sizeof(double) * T * (Q + 1)},
                              {.buf = declined, .len = T}};
        result = status == -2 ? PyErr_NoMemory() : build_chunk(parts);
    }
    free(volumes);
    free(declined);
    return result;
}

static PyObject *steps(PyObject *self, PyObject *args) {
    int enabled = -1;
    (void)self;
    if (!PyArg_ParseTuple(args, "|i", &enabled)) return NULL;
    PyObject *answer = Py_BuildValue("(Oll)", STEPS ? Py_True : Py_False, STEPS_TRIED, STEPS_TAKEN);
    if (enabled >= 0) STEPS = enabled != 0;
    STEPS_TRIED = STEPS_TAKEN = 0;
    return answer;
}

static PyMethodDef methods[] = {
    {"steps", steps, METH_VARARGS,
     "steps(enabled=-1) -> (enabled, tried, taken)\n\n"
     "Whether triplet_volumes and chunk_volumes build each prevailing and calibration-case hull\n"
     "after the first from the previous one's faces (hull_step), and how many such steps were\n"
     "tried and taken (the others built from scratch) in this process since the last call; then\n"
     "turns stepping on (1) or off (0) when given, and resets the counts."},
    {"hull", hull, METH_VARARGS,
     "hull(points, flat_fraction) -> (volume, vertices) or None\n\n"
     "Convex hull of a C-contiguous float64 (n, 3) array by Quickhull: its volume\n"
     "(points' units cubed) and its vertex indices (bytes of int32, ascending).\n"
     "None where the caller must use Qhull: a flat or nearly flat cloud (volume\n"
     "not above flat_fraction times the cube of the bounding box's longest side)\n"
     "or a numerical inconsistency."},
    {"triplet_volumes", triplet_volumes, METH_VARARGS,
     "triplet_volumes(clouds, gains, reduce, shared, flat_fraction) -> bytes or None\n\n"
     "The Q + 1 gamut volumes of one sensor triplet (float64 bytes): clouds (P, n, 3)\n"
     "are the prevailing clouds, gains (P, Q, 3) Eq. 4's per-channel gains; with\n"
     "reduce each cloud is first cut to its hull vertices (shared: all clouds share\n"
     "the first one's, as for the impulse sensor); case q is the hull of every\n"
     "cloud scaled by its gains for q, the last volume the hull of the cases'\n"
     "vertices. None when any hull is declined (see hull): the caller redoes the\n"
     "triplet with Qhull where needed."},
    {"chunk_volumes", chunk_volumes, METH_VARARGS,
     "chunk_volumes(signal, channels, gains, reduce, shared, flat_fraction) -> (bytes, bytes)\n\n"
     "triplet_volumes for T triplets at once, their clouds gathered from signal (J, P, n),\n"
     "the single-sensor responses per position; channels (T, 3) int64 are each triplet's\n"
     "positions for R, G, B, gains (T, P, Q, 3) their Eq. 4 gains. Returns the volumes\n"
     "(T x (Q + 1) float64 bytes, NaN where declined) and one declined flag per triplet\n"
     "(bytes): the caller redoes those with Qhull where needed."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_hull3d",
                                    "Quickhull in 3-D for the Stage 3 search (see skinrender.search).", -1, methods, NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit__hull3d(void) { return PyModule_Create(&module); }

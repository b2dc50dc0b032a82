/* Counts (and optionally records) the rays Mitsuba 3 casts through the Embree it bundles.
 *
 * Built and preloaded by scripts/mitsuba_rays/run.sh (see there). Mitsuba's wheel puts Embree's
 * API in the C++ namespace `mitsuba`, so the wrapped entry points carry mangled names; each wrapper
 * counts the call and its active lanes, times the call (two clock reads), and passes it on to
 * the real function, found with dlsym in the already loaded libembree3.so (MITSUBA_EMBREE).
 * With RAYDUMP=PREFIX set, every 16-wide call's valid mask and ray (before the call) are also
 * appended to PREFIX.intersect / PREFIX.occluded: 64 bytes of mask, then the 768 bytes of
 * RTCRay16 (org x/y/z, tnear, dir x/y/z, time, tfar, mask, id, flags; 16 lanes each), then 64
 * bytes whose first word is the call's context flags (1: RTC_INTERSECT_CONTEXT_FLAG_COHERENT).
 * The totals go to stderr at exit as lines starting with RAYCOUNT. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static atomic_long calls[2][17], lanes[2][17], nanos[2], coherent[2];
static FILE *dump[2];

static void *embree(void) {
    static void *h = 0;
    if (!h) {
        const char *path = getenv("MITSUBA_EMBREE");
        h = path ? dlopen(path, RTLD_NOW | RTLD_NOLOAD) : 0;
        if (!h) {
            fprintf(stderr, "mitsuba_rays: MITSUBA_EMBREE is not a loaded libembree3.so\n");
            abort();
        }
    }
    return h;
}

static long now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1000000000L + t.tv_nsec;
}

static void record(int kind, const int *valid, const void *ray, const void *ctx) {
    const char *prefix = getenv("RAYDUMP");
    if (!prefix) return;
    if (!dump[kind]) {
        char name[4096];
        snprintf(name, sizeof name, "%s.%s", prefix, kind ? "occluded" : "intersect");
        dump[kind] = fopen(name, "wb");
        if (!dump[kind]) { perror(name); abort(); }
    }
    fwrite(valid, 4, 16, dump[kind]);
    fwrite(ray, 4, 16 * 12, dump[kind]);
    unsigned context[16] = {*(const unsigned *)ctx};
    fwrite(context, 4, 16, dump[kind]);
}

#define WRAP(N, NAME, KIND)                                                        \
    void NAME(const int *valid, void *scene, void *ctx, void *ray) {               \
        static void (*real)(const int *, void *, void *, void *) = 0;              \
        if (!real) real = dlsym(embree(), #NAME);                                  \
        long active = 0;                                                           \
        for (int i = 0; i < N; i++) active += valid[i] != 0;                       \
        if (N == 16) record(KIND, valid, ray, ctx);                                     \
        atomic_fetch_add(&coherent[KIND], (*(const unsigned *)ctx & 1) != 0);     \
        atomic_fetch_add(&calls[KIND][N], 1);                                      \
        atomic_fetch_add(&lanes[KIND][N], active);                                 \
        long t0 = now();                                                           \
        real(valid, scene, ctx, ray);                                              \
        atomic_fetch_add(&nanos[KIND], now() - t0);                                \
    }

#define WRAP1(NAME, KIND)                                                          \
    void NAME(void *scene, void *ctx, void *ray) {                                 \
        static void (*real)(void *, void *, void *) = 0;                           \
        if (!real) real = dlsym(embree(), #NAME);                                  \
        atomic_fetch_add(&calls[KIND][1], 1);                                      \
        atomic_fetch_add(&lanes[KIND][1], 1);                                      \
        long t0 = now();                                                           \
        real(scene, ctx, ray);                                                     \
        atomic_fetch_add(&nanos[KIND], now() - t0);                                \
    }

WRAP(16, _ZN7mitsuba14rtcIntersect16EPKiPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_11RTCRayHit16E, 0)
WRAP(16, _ZN7mitsuba13rtcOccluded16EPKiPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_8RTCRay16E, 1)
WRAP(8, _ZN7mitsuba13rtcIntersect8EPKiPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_10RTCRayHit8E, 0)
WRAP(8, _ZN7mitsuba12rtcOccluded8EPKiPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_7RTCRay8E, 1)
WRAP(4, _ZN7mitsuba13rtcIntersect4EPKiPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_10RTCRayHit4E, 0)
WRAP(4, _ZN7mitsuba12rtcOccluded4EPKiPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_7RTCRay4E, 1)
WRAP1(_ZN7mitsuba13rtcIntersect1EPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_9RTCRayHitE, 0)
WRAP1(_ZN7mitsuba12rtcOccluded1EPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_6RTCRayE, 1)

/* The scene settings Mitsuba chooses (printed, then passed on). */
#define SETTING(NAME, WHAT)                                                        \
    void NAME(void *scene, int value) {                                            \
        static void (*real)(void *, int) = 0;                                      \
        if (!real) real = dlsym(embree(), #NAME);                                  \
        fprintf(stderr, "RAYCOUNT scene %s = %d\n", WHAT, value);                  \
        real(scene, value);                                                        \
    }
SETTING(_ZN7mitsuba16rtcSetSceneFlagsEPNS_10RTCSceneTyENS_13RTCSceneFlagsE, "flags")
SETTING(_ZN7mitsuba23rtcSetSceneBuildQualityEPNS_10RTCSceneTyENS_15RTCBuildQualityE, "build quality")

__attribute__((destructor)) static void report(void) {
    for (int k = 0; k < 2; k++) {
        long c = 0, l = 0;
        for (int n = 1; n <= 16; n++) {
            c += calls[k][n];
            l += lanes[k][n];
            if (calls[k][n])
                fprintf(stderr, "RAYCOUNT %s width %d: %ld calls, %ld rays\n",
                        k ? "occluded" : "intersect", n, calls[k][n], lanes[k][n]);
        }
        if (c)
            fprintf(stderr, "RAYCOUNT %s: %ld calls (%ld marked coherent), %ld rays, %.3f s in Embree\n",
                    k ? "occluded" : "intersect", c, coherent[k], l, nanos[k] * 1e-9);
        if (dump[k]) fclose(dump[k]);
    }
}

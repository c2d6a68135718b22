/* SPDX-License-Identifier: GPL-3.0-or-later */
/* 3MF writer (3MF Consortium, "3D Manufacturing Format, Core
 * Specification" 1.x): the package (OPC zip with 3D/3dmodel.model) is
 * built by lib3mf 1.8 through its plain C interface and written into a
 * memory stream, whose bytes then go through our sink, so the file is
 * atomic like every other format (temporary file, fsync, rename).
 *
 * Core spec, what is used:
 * - 3.4 <model unit="...">: micron, millimeter, centimeter, inch, foot,
 *   meter; from the model's `units`, millimeter (the spec's default) when
 *   none. Any other unit is refused rather than silently rescaled.
 * - 4 and 4.1 (Meshes) <object type="model">: one mesh object per part,
 *   named after it; a model object must be a closed, consistently oriented
 *   2-manifold, so open parts (isoparametric surfaces) are refused before
 *   any output exists. Triangles are counter-clockwise seen from outside
 *   (the mesh's own order), vertex indices local to the object (the
 *   part's vertex range).
 * - 3.4.1 metadata "Title": the model name.
 * - 3.4.3 (Build Instructions) <build>: one <item> per object, no
 *   transform.
 * lib3mf stores float32 coordinates, the precision STL readers see, and
 * prints them cut (not rounded) to 6 decimals: at most 1e-6 off.
 *
 * lib3mf gives every object, build item and the build a random UUID (3MF
 * Production extension); they are set here from the part index so the
 * output is deterministic, as every writer's must be.
 *
 * No exception crosses into C: every entry runs in coons::guard, and the
 * stream callbacks called from inside lib3mf catch everything. */
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <Model/COM/NMR_DLLInterfaces.h>

#include "cxx_guard.hpp"

extern "C" {
#include "writer.h"
}

namespace {

/* One lib3mf handle, released on scope exit. */
struct handle {
    NMR::PLib3MFBase *p = nullptr;
    handle() = default;
    handle(const handle &) = delete;
    handle &operator=(const handle &) = delete;
    ~handle()
    {
        if (p) NMR::lib3mf_release(p);
    }
};

/* The seekable memory stream lib3mf writes the zip package into. */
struct memstream {
    std::vector<unsigned char> bytes;
    uint64_t pos = 0;
    bool nomem = false;
};

/* lib3mf's callback types (ExportStream_WriteCallbackType): 0 is success. */
extern "C" unsigned int mem_write(unsigned char *data, unsigned int n, void *user) noexcept
{
    memstream *s = static_cast<memstream *>(user);
    try {
        if (s->pos + n > s->bytes.size()) s->bytes.resize(s->pos + n);
        if (n) std::memcpy(s->bytes.data() + s->pos, data, n);
        s->pos += n;
        return 0;
    } catch (...) {
        s->nomem = true;
        return 1;
    }
}

extern "C" unsigned int mem_seek(unsigned long long pos, void *user) noexcept
{
    memstream *s = static_cast<memstream *>(user);
    if (pos > s->bytes.size()) return 1;
    s->pos = pos;
    return 0;
}

/* The status and message of a failed lib3mf call on `obj` (NULL: none). */
coons_status lib3mf_error(coons_error *err, NMR::PLib3MFBase *obj, const char *doing, int rc)
{
    DWORD code = (DWORD)rc;
    LPCSTR msg = nullptr;
    if (obj) NMR::lib3mf_getlasterror(obj, &code, &msg);
    return coons__error_set(err, COONS_E_INTERNAL, "lib3mf could not %s: %s (error 0x%lx)", doing,
                            msg && msg[0] ? msg : "no message", (unsigned long)code);
}

#define CALL(obj, doing, expr)                                                 \
    do {                                                                       \
        int rc_ = (expr);                                                      \
        if (rc_ != LIB3MF_OK) return lib3mf_error(err, (obj), (doing), rc_);   \
    } while (0)

bool same_word(const char *a, const char *b)
{
    for (; *a && *b; a++, b++)
        if (std::tolower((unsigned char)*a) != *b) return false;
    return *a == *b;
}

/* The 3MF unit of the model's `units` text (core spec 3.4), or -1. */
int unit_of(const char *units)
{
    static const struct {
        const char *word;
        int unit;
    } UNITS[] = {
        {"", NMR::MODELUNIT_MILLIMETER},   {"mm", NMR::MODELUNIT_MILLIMETER},
        {"millimeter", NMR::MODELUNIT_MILLIMETER}, {"millimetre", NMR::MODELUNIT_MILLIMETER},
        {"millimeters", NMR::MODELUNIT_MILLIMETER}, {"millimetres", NMR::MODELUNIT_MILLIMETER},
        {"um", NMR::MODELUNIT_MICROMETER}, {"\xc2\xb5m", NMR::MODELUNIT_MICROMETER},
        {"micron", NMR::MODELUNIT_MICROMETER}, {"microns", NMR::MODELUNIT_MICROMETER},
        {"micrometer", NMR::MODELUNIT_MICROMETER}, {"micrometre", NMR::MODELUNIT_MICROMETER},
        {"cm", NMR::MODELUNIT_CENTIMETER}, {"centimeter", NMR::MODELUNIT_CENTIMETER},
        {"centimetre", NMR::MODELUNIT_CENTIMETER}, {"centimeters", NMR::MODELUNIT_CENTIMETER},
        {"centimetres", NMR::MODELUNIT_CENTIMETER},
        {"in", NMR::MODELUNIT_INCH}, {"inch", NMR::MODELUNIT_INCH},
        {"inches", NMR::MODELUNIT_INCH},
        {"ft", NMR::MODELUNIT_FOOT}, {"foot", NMR::MODELUNIT_FOOT}, {"feet", NMR::MODELUNIT_FOOT},
        {"m", NMR::MODELUNIT_METER}, {"meter", NMR::MODELUNIT_METER},
        {"metre", NMR::MODELUNIT_METER}, {"meters", NMR::MODELUNIT_METER},
        {"metres", NMR::MODELUNIT_METER},
    };
    for (const auto &u : UNITS)
        if (same_word(units, u.word)) return u.unit;
    return -1;
}

/* Edges of part i that are not run exactly once each way by its
 * triangles (boundary, non-manifold or misoriented), counted on directed
 * vertex pairs, plus the edges of degenerate triangles: 0 for a closed,
 * oriented shell whose every edge has two triangles. */
size_t bad_edges(const coons_mesh *m, size_t i)
{
    size_t tf, tc, vf, vc;
    coons_mesh_part_range(m, i, &tf, &tc, &vf, &vc);
    const uint32_t *t = coons_mesh_triangles(m) + 3 * tf;
    std::vector<uint64_t> fwd;
    fwd.reserve(3 * tc);
    size_t bad = 0;
    for (size_t k = 0; k < tc; k++)
        for (int e = 0; e < 3; e++) {
            uint64_t a = t[3 * k + (size_t)e], b = t[3 * k + (size_t)(e + 1) % 3];
            bad += a == b; /* a degenerate triangle */
            fwd.push_back(a << 32 | b);
        }
    std::sort(fwd.begin(), fwd.end());
    for (size_t k = 0; k < fwd.size(); k++) {
        uint64_t rev = fwd[k] << 32 | fwd[k] >> 32;
        bool repeated = (k > 0 && fwd[k] == fwd[k - 1]) ||
                        (k + 1 < fwd.size() && fwd[k] == fwd[k + 1]);
        if (repeated || !std::binary_search(fwd.begin(), fwd.end(), rev)) bad++;
    }
    return bad;
}

coons_status check(const coons_mesh *m, coons_error *err)
{
    size_t np = coons_mesh_part_count(m);
    if (np == 0)
        return coons__error_set(err, COONS_E_INVALID,
                                "3MF needs at least one object; the mesh has no part");
    for (size_t i = 0; i < np; i++) {
        size_t tf, tc, vf, vc;
        coons_mesh_part_range(m, i, &tf, &tc, &vf, &vc);
        if (vc > UINT32_MAX || tc > UINT32_MAX)
            return coons__error_set(err, COONS_E_LIMIT,
                                    "3MF (lib3mf) holds at most 2^32-1 vertices and triangles "
                                    "per object; part '%s' has %zu and %zu",
                                    coons_mesh_part_name(m, i), vc, tc);
        size_t bad = tc ? bad_edges(m, i) : 0;
        if (tc == 0 || bad)
            return coons__error_set(err, COONS_E_UNSUPPORTED,
                                    "3MF objects are closed solids (3MF core specification "
                                    "4.1, Meshes); "
                                    "part '%s' is %s (write it as .off, .vtu or .scad)",
                                    coons_mesh_part_name(m, i),
                                    tc ? "not a closed, oriented surface" : "empty");
    }
    return COONS_OK;
}

/* Deterministic version-4-shaped UUID of (kind, index). */
std::string uuid_of(unsigned kind, size_t index)
{
    char buf[40];
    std::snprintf(buf, sizeof buf, "c0025000-%04x-4000-8000-%012llx", kind & 0xffffu,
                  (unsigned long long)index & 0xffffffffffffull);
    return buf;
}

coons_status write(const coons_mesh *m, const coons__wopts *o, coons__sink *s)
{
    coons_error *err = s->err;
    int unit = unit_of(o->units);
    if (unit < 0)
        return s->status = coons__error_set(
                   err, COONS_E_UNSUPPORTED,
                   "cannot write '%s': 3MF carries the units micron, millimeter, centimeter, "
                   "inch, foot and meter (core specification 3.4); the model's units '%s' are "
                   "none of them",
                   s->what, o->units);
    coons_status st = [&]() -> coons_status {
        handle model;
        CALL(nullptr, "create a model", NMR::lib3mf_createmodel(&model.p));
        CALL(model.p, "set the unit", NMR::lib3mf_model_setunit(model.p, (DWORD)unit));
        CALL(model.p, "set the build UUID",
             NMR::lib3mf_model_setbuilduuidutf8(model.p, uuid_of(0, 0).c_str()));
        CALL(model.p, "add metadata",
             NMR::lib3mf_model_addmetadatautf8(model.p, "Title", o->name));
        const double *xyz = coons_mesh_vertices(m);
        const uint32_t *tri = coons_mesh_triangles(m);
        std::vector<NMR::MODELMESHVERTEX> v;
        std::vector<NMR::MODELMESHTRIANGLE> t;
        for (size_t i = 0; i < coons_mesh_part_count(m); i++) {
            size_t tf, tc, vf, vc;
            coons_mesh_part_range(m, i, &tf, &tc, &vf, &vc);
            v.resize(vc);
            t.resize(tc);
            for (size_t k = 0; k < vc; k++)
                for (int c = 0; c < 3; c++)
                    v[k].m_fPosition[c] = (float)xyz[3 * (vf + k) + (size_t)c];
            for (size_t k = 0; k < tc; k++)
                for (int c = 0; c < 3; c++) {
                    uint32_t g = tri[3 * (tf + k) + (size_t)c];
                    if (g < vf || g - vf >= vc)
                        return coons__error_set(err, COONS_E_INVALID,
                                                "triangle %zu of part '%s' uses vertex %lu "
                                                "outside the part",
                                                k, coons_mesh_part_name(m, i), (unsigned long)g);
                    t[k].m_nIndices[c] = (DWORD)(g - vf);
                }
            handle obj, item;
            CALL(model.p, "add a mesh object", NMR::lib3mf_model_addmeshobject(model.p, &obj.p));
            CALL(obj.p, "name an object",
                 NMR::lib3mf_object_setnameutf8(obj.p, coons_mesh_part_name(m, i)));
            CALL(obj.p, "set an object type",
                 NMR::lib3mf_object_settype(obj.p, NMR::MODELOBJECTTYPE_MODEL));
            CALL(obj.p, "set an object UUID",
                 NMR::lib3mf_object_setuuidutf8(obj.p, uuid_of(1, i).c_str()));
            CALL(obj.p, "set a mesh",
                 NMR::lib3mf_meshobject_setgeometry(obj.p, v.data(), (DWORD)vc, t.data(),
                                                    (DWORD)tc));
            CALL(model.p, "add a build item",
                 NMR::lib3mf_model_addbuilditem(model.p, obj.p, nullptr, &item.p));
            CALL(item.p, "set a build item UUID",
                 NMR::lib3mf_builditem_setuuidutf8(item.p, uuid_of(2, i).c_str()));
        }
        handle writer;
        CALL(model.p, "create a 3MF writer",
             NMR::lib3mf_model_querywriter(model.p, "3mf", &writer.p));
        memstream mem;
        int rc = NMR::lib3mf_writer_writetocallback(writer.p, (void *)mem_write, (void *)mem_seek,
                                                    &mem);
        if (mem.nomem) return coons__error_nomem(err);
        if (rc != LIB3MF_OK) return lib3mf_error(err, writer.p, "write the package", rc);
        const unsigned char *p = mem.bytes.data();
        size_t left = mem.bytes.size();
        /* In buffer-sized pieces, so that `cancel` is polled between them. */
        while (left > 0 && coons__sink_ok(s)) {
            size_t k = left < COONS__SINK_BUFSIZE ? left : COONS__SINK_BUFSIZE;
            if (!coons__sink_put(s, p, k)) break;
            p += k;
            left -= k;
        }
        return s->status;
    }();
    if (st != COONS_OK && s->status == COONS_OK) s->status = st;
    return s->status;
}

const coons::guard_text WRITE_TEXT = {COONS_E_INTERNAL, "3MF writer: ",
                                      "3MF writer: unknown exception"};

} // namespace

extern "C" coons_status coons__check_3mf(const coons_mesh *m, coons_error *err)
{
    return coons::guard("coons__check_3mf", err, WRITE_TEXT, [&] { return check(m, err); });
}

extern "C" coons_status coons__write_3mf(const coons_mesh *m, const coons__wopts *o,
                                         coons__sink *s)
{
    coons_status st =
        coons::guard("coons__write_3mf", s->err, WRITE_TEXT, [&] { return write(m, o, s); });
    if (st != COONS_OK && s->status == COONS_OK) s->status = st;
    return s->status;
}

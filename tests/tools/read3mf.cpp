/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lib3mf 1.8's reader behind the C interface of read3mf.h (tests only). */
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <Model/COM/NMR_DLLInterfaces.h>

#include "read3mf.h"

using namespace NMR;

namespace {

struct handle {
    PLib3MFBase *p = nullptr;
    ~handle()
    {
        if (p) lib3mf_release(p);
    }
};

int fail(char *msg, size_t cap, PLib3MFBase *obj, const char *what)
{
    DWORD code = 0;
    LPCSTR text = nullptr;
    if (obj) lib3mf_getlasterror(obj, &code, &text);
    std::snprintf(msg, cap, "%s: %s (0x%x)", what, text ? text : "?", code);
    return -1;
}

int read(const char *path, r3mf *out, char *msg, size_t cap)
{
    handle model, reader;
    if (lib3mf_createmodel(&model.p) != LIB3MF_OK) return fail(msg, cap, nullptr, "createmodel");
    if (lib3mf_model_queryreader(model.p, "3mf", &reader.p) != LIB3MF_OK)
        return fail(msg, cap, model.p, "queryreader");
    lib3mf_reader_setstrictmodeactive(reader.p, 1);
    if (lib3mf_reader_readfromfileutf8(reader.p, path) != LIB3MF_OK)
        return fail(msg, cap, reader.p, "read");
    DWORD unit = 99;
    lib3mf_model_getunit(model.p, &unit);
    out->unit = (int)unit;
    DWORD nmeta = 0;
    lib3mf_model_getmetadatacount(model.p, &nmeta);
    for (DWORD i = 0; i < nmeta; i++) {
        char key[64] = "";
        ULONG need = 0;
        lib3mf_model_getmetadatakeyutf8(model.p, i, key, sizeof key, &need);
        if (std::strcmp(key, "Title") == 0)
            lib3mf_model_getmetadatavalueutf8(model.p, i, out->title, sizeof out->title, &need);
    }
    std::vector<r3mf_object> objs;
    handle it;
    if (lib3mf_model_getmeshobjects(model.p, &it.p) != LIB3MF_OK)
        return fail(msg, cap, model.p, "getmeshobjects");
    BOOL more = 0;
    while (lib3mf_resourceiterator_movenext(it.p, &more) == LIB3MF_OK && more) {
        handle res;
        if (lib3mf_resourceiterator_getcurrent(it.p, &res.p) != LIB3MF_OK)
            return fail(msg, cap, it.p, "getcurrent");
        r3mf_object o{};
        DWORD id = 0, type = 0, nv = 0, nt = 0;
        ULONG need = 0;
        BOOL ok = 0;
        lib3mf_resource_getresourceid(res.p, &id);
        lib3mf_object_gettype(res.p, &type);
        lib3mf_object_getnameutf8(res.p, o.name, sizeof o.name, &need);
        lib3mf_meshobject_getvertexcount(res.p, &nv);
        lib3mf_meshobject_gettrianglecount(res.p, &nt);
        lib3mf_meshobject_ismanifoldandoriented(res.p, &ok);
        o.id = id;
        o.type = (int)type;
        o.nv = nv;
        o.nt = nt;
        o.manifold = ok != 0;
        std::vector<MODELMESHVERTEX> v(nv ? nv : 1);
        std::vector<MODELMESHTRIANGLE> t(nt ? nt : 1);
        if (nv && lib3mf_meshobject_getvertices(res.p, v.data(), nv, nullptr) != LIB3MF_OK)
            return fail(msg, cap, res.p, "getvertices");
        if (nt && lib3mf_meshobject_gettriangleindices(res.p, t.data(), nt, nullptr) != LIB3MF_OK)
            return fail(msg, cap, res.p, "gettriangleindices");
        o.v = static_cast<float *>(std::malloc(3 * sizeof(float) * (nv ? nv : 1)));
        o.t = static_cast<uint32_t *>(std::malloc(3 * sizeof(uint32_t) * (nt ? nt : 1)));
        for (DWORD k = 0; k < nv; k++)
            for (int c = 0; c < 3; c++) o.v[3 * k + c] = v[k].m_fPosition[c];
        for (DWORD k = 0; k < nt; k++)
            for (int c = 0; c < 3; c++) o.t[3 * k + c] = t[k].m_nIndices[c];
        objs.push_back(o);
    }
    std::vector<uint32_t> items;
    handle bi;
    if (lib3mf_model_getbuilditems(model.p, &bi.p) != LIB3MF_OK)
        return fail(msg, cap, model.p, "getbuilditems");
    while (lib3mf_builditemiterator_movenext(bi.p, &more) == LIB3MF_OK && more) {
        handle item;
        lib3mf_builditemiterator_getcurrent(bi.p, &item.p);
        DWORD id = 0;
        BOOL tr = 0;
        lib3mf_builditem_getobjectresourceid(item.p, &id);
        lib3mf_builditem_hasobjecttransform(item.p, &tr);
        if (tr) out->item_transform = 1;
        items.push_back(id);
    }
    out->nobj = objs.size();
    out->obj = static_cast<r3mf_object *>(std::malloc(sizeof(r3mf_object) * (objs.size() + 1)));
    std::memcpy(out->obj, objs.data(), sizeof(r3mf_object) * objs.size());
    out->nitems = items.size();
    out->item = static_cast<uint32_t *>(std::malloc(sizeof(uint32_t) * (items.size() + 1)));
    std::memcpy(out->item, items.data(), sizeof(uint32_t) * items.size());
    return 0;
}

} // namespace

extern "C" int r3mf_read(const char *path, r3mf *out, char *msg, size_t cap)
{
    std::memset(out, 0, sizeof *out);
    try {
        return read(path, out, msg, cap);
    } catch (...) {
        std::snprintf(msg, cap, "exception while reading %s", path);
        return -1;
    }
}

extern "C" void r3mf_free(r3mf *m)
{
    for (size_t i = 0; i < m->nobj; i++) {
        std::free(m->obj[i].v);
        std::free(m->obj[i].t);
    }
    std::free(m->obj);
    std::free(m->item);
    std::memset(m, 0, sizeof *m);
}

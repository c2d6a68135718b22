/* SPDX-License-Identifier: GPL-3.0-or-later */
/* What the volume mesh's files share (volume_impl.h): growing arrays,
 * copying and checking names. */
#include <stdio.h>
#include <string.h>

#include "volume_impl.h"

int coons__vgrow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return 1;
    size_t nc = *cap ? *cap : 16;
    while (nc < need) {
        if (nc > SIZE_MAX / 2) return 0;
        nc *= 2;
    }
    if (nc > SIZE_MAX / elem) return 0;
    void *q = coons__realloc(*p, nc * elem);
    if (!q) return 0;
    *p = q;
    *cap = nc;
    return 1;
}

char *coons__vstrdup(const char *s)
{
    size_t n = strlen(s);
    char *d = coons__malloc(n + 1);
    if (d) memcpy(d, s, n + 1);
    return d;
}

coons_status coons__vname_check(const char *name, const char *what, const void *taken, size_t n,
                                size_t stride, coons_error *err)
{
    if (!name || !name[0]) return coons__error_set(err, COONS_E_INVALID, "%s has no name", what);
    size_t len = strlen(name);
    if (len > COONS_VOLUME_NAME_MAX)
        return coons__error_set(err, COONS_E_INVALID, "%s name of %zu bytes: at most %d", what,
                                len, COONS_VOLUME_NAME_MAX);
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)name[i];
        if (c < 0x20 || c == 0x7f)
            return coons__error_set(err, COONS_E_INVALID,
                                    "%s name '%.*s...' has the control character 0x%02x", what,
                                    (int)i, name, c);
    }
    for (size_t i = 0; taken && i < n; i++) {
        const char *other;
        memcpy(&other, (const char *)taken + i * stride, sizeof other);
        if (strcmp(other, name) == 0)
            return coons__error_set(err, COONS_E_INVALID, "%s name '%s' is already taken", what,
                                    name);
    }
    return COONS_OK;
}

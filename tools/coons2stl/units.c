/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Units (coons2stl(1), "UNITS"): the model's "units" (coons-model(5)) go
 * into every format that carries them (3MF's unit, the .inp heading, the
 * comments of STL, OFF and SCAD), but the readers of STL, OFF and SCAD
 * (slicers, OpenSCAD) take every number as millimetres. So a mesh in
 * other units written to one of those is warned about once, naming the
 * unit; --scale-to UNIT multiplies every written coordinate by the length
 * of the model's unit in UNIT and labels the output UNIT (the tolerance,
 * -t and --frame stay in model units, as the model is read). The unit
 * names are those of the 3MF core specification 3.4 (micron, millimeter,
 * centimeter, inch, foot, meter).
 */
#include <stdio.h>
#include <strings.h>

#include "cli.h"

static const struct {
    const char *name;
    double mm;
} UNITS[] = {
    {"um", 1e-3},   {"micron", 1e-3},      {"microns", 1e-3},     {"micrometer", 1e-3},
    {"micrometre", 1e-3}, {"micrometers", 1e-3}, {"micrometres", 1e-3},
    {"mm", 1.0},    {"millimeter", 1.0},   {"millimetre", 1.0},   {"millimeters", 1.0},
    {"millimetres", 1.0},
    {"cm", 10.0},   {"centimeter", 10.0},  {"centimetre", 10.0},  {"centimeters", 10.0},
    {"centimetres", 10.0},
    {"in", 25.4},   {"inch", 25.4},        {"inches", 25.4},
    {"ft", 304.8},  {"foot", 304.8},       {"feet", 304.8},
    {"m", 1000.0},  {"meter", 1000.0},     {"metre", 1000.0},     {"meters", 1000.0},
    {"metres", 1000.0},
};

double cli_unit_mm(const char *unit)
{
    for (size_t i = 0; unit && i < sizeof UNITS / sizeof UNITS[0]; i++)
        if (strcasecmp(unit, UNITS[i].name) == 0) return UNITS[i].mm;
    return 0.0;
}

int cli_format_unitless(coons_format f)
{
    return f == COONS_FORMAT_STL_BINARY || f == COONS_FORMAT_STL_ASCII ||
           f == COONS_FORMAT_OFF || f == COONS_FORMAT_SCAD;
}

int cli_resolve_units(options *o, const coons_model *m)
{
    const char *units = coons_model_units(m);
    o->scale = 1.0;
    o->units_out = units;
    if (o->scale_to) {
        double from = cli_unit_mm(units), to = cli_unit_mm(o->scale_to);
        if (from == 0.0) {
            fprintf(stderr,
                    "%s: --scale-to %s: the model's units '%s' are not a known length (um, mm, "
                    "cm, in, ft, m or their names); nothing was written\n",
                    PROG, o->scale_to, units);
            return EXIT_INPUT;
        }
        o->scale = from / to;
        o->units_out = o->scale_to;
    }
    /* A mesh goes to -o: every mode but --eval and --info (whose -o is a
     * volume format, which are not unitless). */
    int writes = !o->eval && !o->info;
    if (writes && cli_format_unitless(o->format) && cli_unit_mm(o->units_out) != 1.0)
        cli_message(1,
                    "the model's units are '%s', but the format '%s' has no units (its "
                    "readers take millimetres): the coordinates are written in '%s'; "
                    "--scale-to mm converts them",
                    o->units_out, coons_format_name(o->format), o->units_out);
    return -1;
}

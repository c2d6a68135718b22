/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Exact solids through Open CASCADE (OCCT 7.6, LGPL-2.1 with an exception):
 * the one translation unit of the OCCT layer (coons/brep.h describes what
 * is written). Each body becomes a solid whose faces are the B-spline or
 * NURBS forms of its boundary faces (coons_body_face_to_nurbs()), sewn
 * along their shared edges; a union fuses the solids with OCCT's Boolean;
 * every solid is checked before the file is made. STEP (AP214 or AP242),
 * IGES (BRep mode) and BREP text are made in memory and go through the
 * sink, so the file is atomic like every other format.
 *
 * What the prototypes of issue 26 found, and how this file answers:
 * - OCCT prints through Message printers: they are removed once, so the
 *   library prints nothing.
 * - STEP's and IGES's writers send reals with 12 digits: the file is sent
 *   here with the writers' own StepData_StepWriter / IGESData_IGESWriter
 *   whose FloatWriter is given 17 significant digits ("%#.17G": the '#'
 *   keeps the decimal point STEP's reals need; the FloatWriter's zero
 *   suppression is not used: in OCCT 7.6 it cuts 0.35355339059327379 to
 *   0.3535533905932 and 1e-20 to 9.9999999999999, exponent lost).
 * - The schema (write.step.schema) counts only when set after
 *   STEPControl_Controller::Init() and before the model is made: the model
 *   is made again after the setting.
 * - Unit parameters and controllers are process-wide (Interface_Static):
 *   writes hold one mutex.
 * - OCCT throws Standard_Failure, which is no std::exception: it is caught
 *   inside each entry and reported; coons::guard catches everything else.
 * - An inside-out solid still reads back with a positive volume in other
 *   programs: the orientation is fixed here from OCCT's signed volume
 *   before writing (faces reversed), not left to readers. */
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include <BOPAlgo_GlueEnum.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <GProp_GProps.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IGESCAFControl_Writer.hxx>
#include <IGESControl_Controller.hxx>
#include <APIHeaderSection_MakeHeader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepAP214.hxx>
#include <StepAP214_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TCollection_ExtendedString.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

#include "cxx_guard.hpp"

extern "C" {
#include "coons/version.h"
#include "writer.h"
}

namespace {

/* A coons_nurbs released on scope exit. */
struct nurbs_form {
    coons_nurbs n{};
    nurbs_form() = default;
    nurbs_form(const nurbs_form &) = delete;
    nurbs_form &operator=(const nurbs_form &) = delete;
    ~nurbs_form() { coons_nurbs_free(&n); }
};

/* A failure to report: status and message (formatted into err by the entry). */
struct failure {
    coons_status code;
    std::string text;
};

void silence_occt()
{
    static std::once_flag once;
    std::call_once(once, [] {
        const Handle(Message_Messenger) &m = Message::DefaultMessenger();
        m->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
        m->ChangePrinters().Clear();
    });
}

/* One writer at a time: OCCT's translation parameters are process-wide. */
std::mutex &occt_mutex()
{
    static std::mutex m;
    return m;
}

double body_size(const coons_body *b)
{
    double lo[3], hi[3];
    coons_body_control_bbox(b, lo, hi);
    double d = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                         (hi[2] - lo[2]) * (hi[2] - lo[2]));
    return std::isfinite(d) && d > 0 ? d : 1.0;
}

/* The distinct values of a knot vector and their multiplicities. */
void distinct_knots(const double *k, size_t n, std::vector<double> &vals, std::vector<int> &mult)
{
    vals.clear();
    mult.clear();
    for (size_t i = 0; i < n; i++) {
        if (!vals.empty() && k[i] - vals.back() <= 1e-15) {
            mult.back()++;
        } else {
            vals.push_back(k[i]);
            mult.push_back(1);
        }
    }
}

bool collapsed(const coons_nurbs &n, double eps)
{
    size_t np = n.count[0] * n.count[1];
    for (size_t i = 1; i < np; i++)
        for (int c = 0; c < 3; c++)
            if (std::fabs(n.points[3 * i + c] - n.points[c]) > eps) return false;
    return true;
}

/* Whether two faces coincide as point sets (a closed body: a ring whose
 * end faces meet): their 3 x 3 grids agree under one of the 8 symmetries
 * of the square. */
bool coincide(const coons_nurbs &a, const coons_nurbs &b, double eps)
{
    double pa[3][3][3], pb[3][3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double t[2] = {0.5 * i, 0.5 * j};
            coons_nurbs_eval(&a, t, pa[i][j]);
            coons_nurbs_eval(&b, t, pb[i][j]);
        }
    for (int sym = 0; sym < 8; sym++) {
        bool same = true;
        for (int i = 0; i < 3 && same; i++)
            for (int j = 0; j < 3 && same; j++) {
                int x = (sym & 1) ? j : i, y = (sym & 1) ? i : j;
                if (sym & 2) x = 2 - x;
                if (sym & 4) y = 2 - y;
                for (int c = 0; c < 3; c++)
                    if (std::fabs(pa[i][j][c] - pb[x][y][c]) > eps) same = false;
            }
        if (same) return true;
    }
    return false;
}

/* The Geom_BSplineSurface of a face form (rational when it has weights). */
Handle(Geom_BSplineSurface) surface_of(const coons_nurbs &n, double size)
{
    const int nu = (int)n.count[0], nv = (int)n.count[1];
    TColgp_Array2OfPnt poles(1, nu, 1, nv);
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            const double *p = n.points + 3 * ((size_t)i * (size_t)nv + (size_t)j);
            poles.SetValue(i + 1, j + 1, gp_Pnt(p[0], p[1], p[2]));
        }
    std::vector<double> kv[2];
    std::vector<int> km[2];
    for (int d = 0; d < 2; d++)
        distinct_knots(n.knots[d], n.count[d] + (size_t)n.degree[d] + 1, kv[d], km[d]);
    if (coons__occt_wrong_spline_injected() && nu > 2 && nv > 2) {
        /* A wrong spline on purpose (coons_test_hooks.h): an interior
         * control point moved, the edges kept, so the solid stays valid. */
        gp_Pnt p = poles.Value(nu / 2 + 1, nv / 2 + 1);
        poles.SetValue(nu / 2 + 1, nv / 2 + 1, gp_Pnt(p.X() + 1e-4 * size, p.Y(), p.Z()));
    }
    TColStd_Array1OfReal uk(1, (int)kv[0].size()), vk(1, (int)kv[1].size());
    TColStd_Array1OfInteger um(1, (int)km[0].size()), vm(1, (int)km[1].size());
    for (size_t i = 0; i < kv[0].size(); i++) {
        uk.SetValue((int)i + 1, kv[0][i]);
        um.SetValue((int)i + 1, km[0][i]);
    }
    for (size_t i = 0; i < kv[1].size(); i++) {
        vk.SetValue((int)i + 1, kv[1][i]);
        vm.SetValue((int)i + 1, km[1][i]);
    }
    if (n.weights) {
        TColStd_Array2OfReal w(1, nu, 1, nv);
        for (int i = 0; i < nu; i++)
            for (int j = 0; j < nv; j++)
                w.SetValue(i + 1, j + 1, n.weights[(size_t)i * (size_t)nv + (size_t)j]);
        return new Geom_BSplineSurface(poles, w, uk, vk, um, vm, n.degree[0], n.degree[1]);
    }
    return new Geom_BSplineSurface(poles, uk, vk, um, vm, n.degree[0], n.degree[1]);
}

/* The first failed check of a shape, as "face 3: BRepCheck_...". */
std::string first_failed_check(const BRepCheck_Analyzer &ana, const TopoDS_Shape &s)
{
    static const struct {
        TopAbs_ShapeEnum type;
        const char *word;
    } KINDS[] = {{TopAbs_VERTEX, "vertex"}, {TopAbs_EDGE, "edge"}, {TopAbs_WIRE, "wire"},
                 {TopAbs_FACE, "face"},     {TopAbs_SHELL, "shell"}, {TopAbs_SOLID, "solid"}};
    for (const auto &k : KINDS) {
        int index = 0;
        for (TopExp_Explorer ex(s, k.type); ex.More(); ex.Next()) {
            index++;
            const Handle(BRepCheck_Result) &r = ana.Result(ex.Current());
            if (r.IsNull()) continue;
            for (BRepCheck_ListIteratorOfListOfStatus it(r->Status()); it.More(); it.Next()) {
                if (it.Value() == BRepCheck_NoError) continue;
                std::ostringstream os;
                BRepCheck::Print(it.Value(), os);
                std::string text = os.str();
                while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
                return std::string(k.word) + " " + std::to_string(index) + ": " + text;
            }
        }
    }
    return "a sub-shape in context (BRepCheck_Analyzer::IsValid is false)";
}

std::string short_number(double x)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

/* The solid of one body. */
TopoDS_Solid solid_of(const coons_model *m, size_t index, const char *name)
{
    const coons_body *b = coons_model_body(m, index);
    const double size = body_size(b);
    const double eps = 1e-9 * size;
    const double mtol = coons_model_tolerance(m);
    /* A fit (shells) within 1e-5 of the size, or the model's tolerance if finer. */
    const double fit_tol = mtol > 0 ? std::min(mtol, 1e-5 * size) : 1e-5 * size;
    nurbs_form forms[6];
    double worst = 0;
    for (int f = 0; f < 6; f++) {
        coons_error e = COONS_ERROR_INIT;
        coons_status st = coons_body_face_to_nurbs(b, f, fit_tol, &forms[f].n, &e);
        if (st != COONS_OK)
            throw failure{st, std::string("body '") + name + "', face " +
                                  coons_body_face_name(f) + ": " + e.message};
        if (forms[f].n.degree[0] > Geom_BSplineSurface::MaxDegree() ||
            forms[f].n.degree[1] > Geom_BSplineSurface::MaxDegree())
            throw failure{COONS_E_LIMIT, std::string("body '") + name + "', face " +
                                             coons_body_face_name(f) +
                                             ": degree above Open CASCADE's " +
                                             std::to_string(Geom_BSplineSurface::MaxDegree())};
        if (!forms[f].n.exact) worst = std::max(worst, forms[f].n.deviation);
    }
    bool skip[6] = {false, false, false, false, false, false};
    for (int f = 0; f < 6; f++) skip[f] = collapsed(forms[f].n, eps);
    for (int f = 0; f < 6; f++)
        for (int g = f + 1; g < 6; g++)
            if (!skip[f] && !skip[g] && coincide(forms[f].n, forms[g].n, eps + 2 * worst))
                skip[f] = skip[g] = true;
    double sew_tol = std::max(1e-7 * size, 4 * worst);
    if (mtol > 0) sew_tol = std::min(sew_tol, mtol);
    BRepBuilderAPI_Sewing sew(sew_tol);
    int nfaces = 0;
    for (int f = 0; f < 6; f++) {
        if (skip[f]) continue;
        BRepBuilderAPI_MakeFace mf(surface_of(forms[f].n, size), 10 * eps);
        if (!mf.IsDone())
            throw failure{COONS_E_CSG, std::string("body '") + name + "', face " +
                                           coons_body_face_name(f) +
                                           ": Open CASCADE cannot make a face of it"};
        sew.Add(mf.Face());
        nfaces++;
    }
    if (nfaces == 0)
        throw failure{COONS_E_CSG,
                      std::string("body '") + name + "' has no face that is not collapsed"};
    sew.Perform();
    TopoDS_Shape sewed = sew.SewedShape();
    if (sew.NbFreeEdges() > 0)
        throw failure{COONS_E_CSG, std::string("body '") + name + "': its faces do not close (" +
                                       std::to_string(sew.NbFreeEdges()) +
                                       " free edges after sewing at " + short_number(sew_tol) +
                                       ")"};
    TopoDS_Shell shell;
    int nshells = 0;
    for (TopExp_Explorer ex(sewed, TopAbs_SHELL); ex.More(); ex.Next(), nshells++)
        shell = TopoDS::Shell(ex.Current());
    if (nshells != 1)
        throw failure{COONS_E_CSG, std::string("body '") + name + "': sewing made " +
                                       std::to_string(nshells) + " shells, not one"};
    TopoDS_Solid solid = BRepBuilderAPI_MakeSolid(shell).Solid();
    GProp_GProps props;
    BRepGProp::VolumeProperties(solid, props);
    if (props.Mass() < 0) {
        /* Inward faces (a mirrored body): the shell made again of the
         * reversed faces, so that every writer and reader sees it outward. */
        BRep_Builder bb;
        TopoDS_Shell out;
        bb.MakeShell(out);
        for (TopExp_Explorer ex(shell, TopAbs_FACE); ex.More(); ex.Next())
            bb.Add(out, ex.Current().Reversed());
        out.Closed(Standard_True);
        solid = BRepBuilderAPI_MakeSolid(out).Solid();
    }
    BRepCheck_Analyzer ana(solid);
    if (!ana.IsValid())
        throw failure{COONS_E_CSG, std::string("body '") + name +
                                       "': Open CASCADE's check (BRepCheck_Analyzer) finds "
                                       "its solid not valid: " +
                                       first_failed_check(ana, solid)};
    return solid;
}

/* The unit word of Open CASCADE's translation parameters for a model's
 * units ("mm" when none), or NULL. */
const char *occt_unit(const char *units)
{
    static const struct {
        const char *word;
        const char *unit;
    } UNITS[] = {
        {"", "MM"},           {"mm", "MM"},         {"millimeter", "MM"}, {"millimetre", "MM"},
        {"millimeters", "MM"}, {"millimetres", "MM"}, {"um", "UM"},       {"micron", "UM"},
        {"microns", "UM"},     {"micrometer", "UM"},  {"micrometre", "UM"}, {"cm", "CM"},
        {"centimeter", "CM"}, {"centimetre", "CM"},  {"centimeters", "CM"}, {"centimetres", "CM"},
        {"in", "INCH"},       {"inch", "INCH"},      {"inches", "INCH"},  {"ft", "FT"},
        {"foot", "FT"},       {"feet", "FT"},        {"m", "M"},          {"meter", "M"},
        {"metre", "M"},       {"meters", "M"},       {"metres", "M"},
    };
    for (const auto &u : UNITS) {
        const char *a = units, *w = u.word;
        for (; *a && *w; a++, w++)
            if ((*a >= 'A' && *a <= 'Z' ? *a + 32 : *a) != *w) break;
        if (!*a && !*w) return u.unit;
    }
    return nullptr;
}

/* One named top-level shape of the file. */
struct part {
    TopoDS_Shape shape;
    std::string name;
};

Handle(TDocStd_Document) document_of(const std::vector<part> &parts)
{
    Handle(TDocStd_Document) doc = new TDocStd_Document("MDTV-XCAF");
    Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
    for (const part &p : parts) {
        TDF_Label label = tool->AddShape(p.shape, Standard_False);
        TDataStd_Name::Set(label, TCollection_ExtendedString(p.name.c_str(), Standard_True));
    }
    return doc;
}

void send_step(const std::vector<part> &parts, bool ap242, const char *unit, const char *name,
               std::ostream &os)
{
    STEPControl_Controller::Init();
    Interface_Static::SetCVal("write.step.unit", unit);
    Interface_Static::SetCVal("xstep.cascade.unit", unit);
    /* 4: AP214 IS, 5: AP242 DIS; after Init, before the model is made. */
    Interface_Static::SetIVal("write.step.schema", ap242 ? 5 : 4);
    /* No parameter curves in the file: each reader makes its own from the
     * 3-D edges. With them (mode 1) FreeCAD's Boolean check found
     * BOPAlgo_InvalidCurveOnSurface on the three-body union after the round
     * trip (the re-derived edge tolerance below the pcurves' deviation);
     * without, it is clean, and the file half the size. */
    Interface_Static::SetIVal("write.surfacecurve.mode", 0);
    STEPCAFControl_Writer w;
    w.SetNameMode(Standard_True);
    w.ChangeWriter().Model(Standard_True);
    Handle(TDocStd_Document) doc = document_of(parts);
    if (!w.Transfer(doc, STEPControl_AsIs))
        throw failure{COONS_E_CSG, "Open CASCADE's STEP translation failed"};
    Handle(StepData_StepModel) model = w.ChangeWriter().Model();
    /* The same bytes for the same model: no clock, no user name. */
    APIHeaderSection_MakeHeader header(model);
    header.SetName(new TCollection_HAsciiString(name));
    header.SetTimeStamp(new TCollection_HAsciiString("1970-01-01T00:00:00"));
    header.SetAuthorValue(1, new TCollection_HAsciiString(""));
    header.SetOrganizationValue(1, new TCollection_HAsciiString(""));
    header.SetOriginatingSystem(new TCollection_HAsciiString("libcoons " COONS_VERSION_STRING));
    StepData_StepWriter sw(model);
    sw.FloatWriter().SetFormat("%#.17G", Standard_True);
    sw.SendModel(StepAP214::Protocol());
    if (!sw.Print(os)) throw failure{COONS_E_IO, "Open CASCADE's STEP output failed"};
}

void send_iges(const std::vector<part> &parts, const char *unit, const char *name,
               std::ostream &os)
{
    IGESControl_Controller::Init();
    Interface_Static::SetCVal("write.iges.unit", unit);
    Interface_Static::SetCVal("xstep.cascade.unit", unit);
    Interface_Static::SetIVal("write.iges.brep.mode", 1);
    /* Process-wide, and send_step sets it to 0: IGES keeps its parameter
     * curves (mode 1, the default), whatever was written before in this
     * process (a STEP file first changed the next IGES file's bytes). */
    Interface_Static::SetIVal("write.surfacecurve.mode", 1);
    IGESCAFControl_Writer w;
    w.SetNameMode(Standard_True);
    Handle(TDocStd_Document) doc = document_of(parts);
    if (!w.Transfer(doc)) throw failure{COONS_E_CSG, "Open CASCADE's IGES translation failed"};
    w.ComputeModel();
    /* The same bytes for the same model: no clock, no user name. */
    IGESData_GlobalSection gs = w.Model()->GlobalSection();
    gs.SetDate(new TCollection_HAsciiString("19700101.000000"));
    gs.SetLastChangeDate(new TCollection_HAsciiString("19700101.000000"));
    gs.SetAuthorName(new TCollection_HAsciiString(""));
    gs.SetCompanyName(new TCollection_HAsciiString(""));
    gs.SetFileName(new TCollection_HAsciiString(name));
    gs.SetSystemId(new TCollection_HAsciiString("libcoons " COONS_VERSION_STRING));
    w.Model()->SetGlobalSection(gs);
    IGESData_IGESWriter iw(w.Model());
    iw.FloatWriter().SetFormat("%#.17G", Standard_True);
    iw.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
    if (!iw.Print(os)) throw failure{COONS_E_IO, "Open CASCADE's IGES output failed"};
}

coons_status write(const coons_model *m, coons_format format, const coons__wopts *o,
                   coons__sink *s)
{
    silence_occt();
    const char *unit = occt_unit(o->units);
    if (!unit)
        return s->status = coons__error_set(s->err, COONS_E_INVALID,
                                            "units '%s' have no STEP or IGES unit (use mm, cm, m, "
                                            "um, in or ft)",
                                            o->units);
    const size_t nb = coons_model_body_count(m);
    if (nb == 0)
        return s->status = coons__error_set(s->err, COONS_E_INVALID, "the model has no body");
    std::vector<part> parts;
    for (size_t i = 0; i < nb; i++) {
        if (!coons__sink_ok(s)) return s->status;
        const char *name = coons_model_body_name(m, i);
        std::string bname = name && name[0] ? name : "body " + std::to_string(i);
        parts.push_back({solid_of(m, i, bname.c_str()), bname});
    }
    if (coons_model_operation(m) == COONS_OP_UNION && nb > 1) {
        coons_interface *list = nullptr;
        size_t nint = 0;
        coons_error e = COONS_ERROR_INIT;
        bool glue = coons_model_interfaces(m, &list, &nint, &e) == COONS_OK && nint > 0;
        coons_interfaces_free(list);
        TopTools_ListOfShape args, tools;
        args.Append(parts[0].shape);
        for (size_t i = 1; i < nb; i++) tools.Append(parts[i].shape);
        BRepAlgoAPI_Fuse fuse;
        fuse.SetArguments(args);
        fuse.SetTools(tools);
        double mtol = coons_model_tolerance(m);
        if (mtol > 0) fuse.SetFuzzyValue(1e-3 * mtol);
        if (glue) fuse.SetGlue(BOPAlgo_GlueShift);
        fuse.SetRunParallel(Standard_True);
        fuse.Build();
        if (!fuse.IsDone() || fuse.HasErrors())
            throw failure{COONS_E_CSG, "Open CASCADE's Boolean (BRepAlgoAPI_Fuse) could not "
                                       "unite the bodies"};
        TopoDS_Shape fused = fuse.Shape();
        BRepCheck_Analyzer ana(fused);
        if (!ana.IsValid())
            throw failure{COONS_E_CSG,
                          "the union of the bodies: Open CASCADE's check (BRepCheck_Analyzer) "
                          "finds it not valid: " +
                              first_failed_check(ana, fused)};
        std::vector<part> united;
        int k = 0;
        for (TopExp_Explorer ex(fused, TopAbs_SOLID); ex.More(); ex.Next(), k++)
            united.push_back({ex.Current(), std::string(o->name) +
                                                (k ? "_" + std::to_string(k + 1) : "")});
        if (united.empty())
            throw failure{COONS_E_CSG, "the union of the bodies has no solid"};
        parts.swap(united);
    }
    if (!coons__sink_ok(s)) return s->status;
    std::ostringstream os;
    {
        std::lock_guard<std::mutex> lock(occt_mutex());
        if (format == COONS_FORMAT_STEP || format == COONS_FORMAT_STEP_AP242) {
            send_step(parts, format == COONS_FORMAT_STEP_AP242, unit, o->name, os);
        } else if (format == COONS_FORMAT_IGES) {
            send_iges(parts, unit, o->name, os);
        } else {
            BRep_Builder bb;
            TopoDS_Compound c;
            bb.MakeCompound(c);
            for (const part &p : parts) bb.Add(c, p.shape);
            os.precision(17);
            BRepTools::Write(c, os);
        }
    }
    const std::string text = os.str();
    coons__sink_put(s, text.data(), text.size());
    return s->status;
}

const coons::guard_text SOLID_TEXT = {COONS_E_INTERNAL, "solid writer: ",
                                      "solid writer: unknown exception"};

} // namespace

extern "C" coons_status coons__check_solid(coons_error *err)
{
    (void)err;
    return COONS_OK;
}

extern "C" int coons_solid_formats_available(void) { return 1; }

extern "C" coons_status coons__write_solid(const coons_model *m, coons_format format,
                                           const coons__wopts *o, coons__sink *s)
{
    coons_status st = coons::guard("coons__write_solid", s->err, SOLID_TEXT, [&] {
        try {
            return write(m, format, o, s);
        } catch (const failure &f) {
            return coons__error_set(s->err, f.code, "%s", f.text.c_str());
        } catch (const Standard_Failure &f) {
            return coons__error_set(s->err, COONS_E_CSG, "Open CASCADE: %s: %s",
                                    f.DynamicType()->Name(), f.GetMessageString());
        }
    });
    if (st != COONS_OK && s->status == COONS_OK) s->status = st;
    return s->status == COONS_OK ? st : s->status;
}

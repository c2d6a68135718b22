/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * An independent reader of what the solid writer wrote, for
 * tests/cli/test_step.py: Open CASCADE's own STEP, IGES and BREP readers
 * (not the library), its checker and its adaptive volume integration.
 *
 *   occt_check FILE [--gprop]  one line per solid: "solid FACES VALID VOLUME
 *                              SPANS": VOLUME by BRepGProp with --gprop
 *                              (relative error 1e-13 asked, slow; its
 *                              default rule is 3e-3 off on rational faces;
 *                              else nan), SPANS the divergence theorem
 *                              V = 1/3 sum over faces of the integral of
 *                              x . (S_u x S_v), by 16 x 16 Gauss-Legendre
 *                              points on every knot span of every face over
 *                              its whole parameter bounds (faces not trimmed,
 *                              as the writer's per-body solids; not for
 *                              Boolean results); then "shells N"
 *   occt_check FILE [--gprop] --points < points
 *                              after that, "dist D" per point "x y z a b"
 *                              read: the distance to the nearest point of a
 *                              face found, an upper bound of the distance to
 *                              the boundary: by projection
 *                              (ShapeAnalysis_Surface::ValueOfUV; it, like
 *                              BRepExtrema, misses near the corners of
 *                              rational discs), and by evaluating each face
 *                              at (a, b), the point's parameters on its own
 *                              face, under the 8 symmetries of the square
 *                              mapped onto the face's parameter bounds
 */
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include <BRep_Tool.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <algorithm>
#include <utility>
#include <vector>

#include <BRepBndLib.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <Bnd_Box.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <GProp_GProps.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shape.hxx>

/* The integral of x . (S_u x S_v) over a face's whole parameter bounds,
 * signed by the face's orientation: Gauss-Legendre, 16 x 16 points on
 * every knot span (the bounds split at the knots of a B-spline surface). */
static double face_flux(const TopoDS_Face &f)
{
    static const double X[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274,
                                0.6178762444026438, 0.7554044083550030, 0.8656312023878318,
                                0.9445750230732326, 0.9894009349916499};
    static const double W[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                                0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                                0.0622535239386479, 0.0271524594117541};
    Handle(Geom_Surface) s = BRep_Tool::Surface(f);
    double u0, u1, v0, v1;
    BRepTools::UVBounds(f, u0, u1, v0, v1);
    std::vector<double> us{u0, u1}, vs{v0, v1};
    Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(s);
    if (!bs.IsNull()) {
        for (int i = 1; i <= bs->NbUKnots(); i++)
            if (bs->UKnot(i) > u0 && bs->UKnot(i) < u1) us.push_back(bs->UKnot(i));
        for (int i = 1; i <= bs->NbVKnots(); i++)
            if (bs->VKnot(i) > v0 && bs->VKnot(i) < v1) vs.push_back(bs->VKnot(i));
    }
    std::sort(us.begin(), us.end());
    std::sort(vs.begin(), vs.end());
    double sum = 0;
    for (size_t i = 0; i + 1 < us.size(); i++)
        for (size_t j = 0; j + 1 < vs.size(); j++) {
            double uc = 0.5 * (us[i] + us[i + 1]), uh = 0.5 * (us[i + 1] - us[i]);
            double vc = 0.5 * (vs[j] + vs[j + 1]), vh = 0.5 * (vs[j + 1] - vs[j]);
            for (int p = 0; p < 16; p++)
                for (int q = 0; q < 16; q++) {
                    double xu = p < 8 ? -X[7 - p] : X[p - 8], wu = p < 8 ? W[7 - p] : W[p - 8];
                    double xv = q < 8 ? -X[7 - q] : X[q - 8], wv = q < 8 ? W[7 - q] : W[q - 8];
                    gp_Pnt P;
                    gp_Vec du, dv;
                    s->D1(uc + uh * xu, vc + vh * xv, P, du, dv);
                    sum += wu * wv * uh * vh * gp_Vec(P.XYZ()).Dot(du.Crossed(dv));
                }
        }
    return f.Orientation() == TopAbs_REVERSED ? -sum : sum;
}

static bool ends_with(const std::string &s, const std::string &e)
{
    return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        std::fprintf(stderr, "usage: occt_check FILE [--points]\n");
        return 2;
    }
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    try {
        std::string path = argv[1];
        bool gprop = false, points = false;
        for (int i = 2; i < argc; i++) {
            gprop |= std::string(argv[i]) == "--gprop";
            points |= std::string(argv[i]) == "--points";
        }
        TopoDS_Shape shape;
        if (ends_with(path, ".brep")) {
            BRep_Builder b;
            if (!BRepTools::Read(shape, path.c_str(), b)) return 1;
        } else if (ends_with(path, ".igs") || ends_with(path, ".iges")) {
            IGESControl_Reader r;
            if (r.ReadFile(path.c_str()) != IFSelect_RetDone) return 1;
            r.TransferRoots();
            shape = r.OneShape();
        } else {
            STEPControl_Reader r;
            if (r.ReadFile(path.c_str()) != IFSelect_RetDone) return 1;
            r.TransferRoots();
            shape = r.OneShape();
        }
        for (TopExp_Explorer ex(shape, TopAbs_SOLID); ex.More(); ex.Next()) {
            int faces = 0;
            double spans = 0;
            for (TopExp_Explorer f(ex.Current(), TopAbs_FACE); f.More(); f.Next()) {
                faces++;
                spans += face_flux(TopoDS::Face(f.Current()));
            }
            GProp_GProps p;
            if (gprop) BRepGProp::VolumeProperties(ex.Current(), p, 1e-13);
            std::printf("solid %d %d %.17g %.17g\n", faces,
                        BRepCheck_Analyzer(ex.Current()).IsValid() ? 1 : 0,
                        gprop ? p.Mass() : NAN, spans / 3);
        }
        int shells = 0;
        for (TopExp_Explorer ex(shape, TopAbs_SHELL); ex.More(); ex.Next()) shells++;
        std::printf("shells %d\n", shells);
        if (points) {
            /* Faces tried nearest box first; a face whose box is farther
             * than the best distance so far cannot be nearer. */
            std::vector<Handle(ShapeAnalysis_Surface)> faces;
            std::vector<Bnd_Box> boxes;
            std::vector<Handle(Geom_Surface)> surfaces;
            std::vector<std::vector<double>> bounds;
            for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
                const TopoDS_Face &f = TopoDS::Face(ex.Current());
                faces.push_back(new ShapeAnalysis_Surface(BRep_Tool::Surface(f)));
                Bnd_Box bx;
                BRepBndLib::AddOptimal(f, bx, Standard_False, Standard_False);
                boxes.push_back(bx);
                surfaces.push_back(BRep_Tool::Surface(f));
                double u0, u1, v0, v1;
                BRepTools::UVBounds(f, u0, u1, v0, v1);
                bounds.push_back({u0, u1, v0, v1});
            }
            Bnd_Box all;
            BRepBndLib::Add(shape, all);
            const double scale = std::sqrt(all.SquareExtent());
            double x, y, z, a, b;
            std::vector<std::pair<double, size_t>> order(faces.size());
            char line[512];
            while (std::fgets(line, sizeof line, stdin)) {
                int n = std::sscanf(line, "%lf %lf %lf %lf %lf", &x, &y, &z, &a, &b);
                if (n < 3) continue;
                gp_Pnt q(x, y, z);
                for (size_t i = 0; i < faces.size(); i++) order[i] = {boxes[i].Distance(Bnd_Box(q.XYZ(), q.XYZ())), i};
                std::sort(order.begin(), order.end());
                /* the point's own parameters first (cheap); projection only
                 * when no face has the point there */
                double best = -1;
                if (n == 5)
                    for (auto &o : order) {
                        if (best >= 0 && o.first > best) break;
                        const double *r = bounds[o.second].data();
                        for (int sym = 0; sym < 8; sym++) {
                            double s0 = sym & 1 ? b : a, t0 = sym & 1 ? a : b;
                            if (sym & 2) s0 = 1 - s0;
                            if (sym & 4) t0 = 1 - t0;
                            gp_Pnt e = surfaces[o.second]->Value(r[0] + s0 * (r[1] - r[0]),
                                                                 r[2] + t0 * (r[3] - r[2]));
                            double d = e.Distance(q);
                            if (best < 0 || d < best) best = d;
                        }
                    }
                if (best < 0 || best > 1e-12 * scale)
                    for (auto &o : order) {
                        if (best >= 0 && o.first > best) break;
                        gp_Pnt2d uv = faces[o.second]->ValueOfUV(q, 1e-12);
                        double d = faces[o.second]->Value(uv).Distance(q);
                        if (best < 0 || d < best) best = d;
                    }
                std::printf("dist %.17g\n", best);
            }
        }
    } catch (const Standard_Failure &f) {
        std::fprintf(stderr, "occt_check: %s\n", f.GetMessageString());
        return 1;
    }
    return 0;
}

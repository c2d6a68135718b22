/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * An independent reader of what the solid writer wrote, for
 * tests/cli/test_step.py: Open CASCADE's own STEP, IGES and BREP readers
 * (not the library), its checker and its adaptive volume integration.
 *
 *   occt_check FILE            one line per solid: "solid FACES VALID VOLUME"
 *                              (VOLUME by BRepGProp with relative error
 *                              1e-13: the default rule is 3e-3 off on
 *                              rational faces), then "shells N"
 *   occt_check FILE < points   after that, "dist D" per point "x y z" read
 *                              (distance to the nearest solid's boundary)
 */
#include <cstdio>
#include <iostream>
#include <string>

#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
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
            for (TopExp_Explorer f(ex.Current(), TopAbs_FACE); f.More(); f.Next()) faces++;
            GProp_GProps p;
            BRepGProp::VolumeProperties(ex.Current(), p, 1e-13);
            std::printf("solid %d %d %.17g\n", faces, BRepCheck_Analyzer(ex.Current()).IsValid() ? 1 : 0,
                        p.Mass());
        }
        int shells = 0;
        for (TopExp_Explorer ex(shape, TopAbs_SHELL); ex.More(); ex.Next()) shells++;
        std::printf("shells %d\n", shells);
        if (argc > 2) {
            double x, y, z;
            while (std::scanf("%lf %lf %lf", &x, &y, &z) == 3) {
                BRepExtrema_DistShapeShape d(BRepBuilderAPI_MakeVertex(gp_Pnt(x, y, z)).Vertex(),
                                             shape);
                std::printf("dist %.17g\n", d.IsDone() ? d.Value() : -1.0);
            }
        }
    } catch (const Standard_Failure &f) {
        std::fprintf(stderr, "occt_check: %s\n", f.GetMessageString());
        return 1;
    }
    return 0;
}

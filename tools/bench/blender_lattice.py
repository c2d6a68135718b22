# SPDX-License-Identifier: GPL-3.0-or-later
# Run by tools/bench/bench_deform.sh inside `blender -b --factory-startup`:
# imports the STL, deforms it with a Lattice modifier (a 5 x 5 x 5 B-spline
# lattice over the mesh's box, its points moved like a spool: pinched in
# the middle), exports the deformed mesh as binary STL, and prints the time
# of the modifier alone: evaluating the object with the modifier minus
# without it, best of REPEAT (0: no timing, the whole process only).
import sys, time, math
import bpy

argv = sys.argv[sys.argv.index("--") + 1:]
src, dst, repeat = argv[0], argv[1], int(argv[2])
t_start = time.perf_counter()
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_mesh.stl(filepath=src)
obj = bpy.context.selected_objects[0]
t_import = time.perf_counter()
lo = [min(v.co[d] for v in obj.data.vertices) for d in range(3)]
hi = [max(v.co[d] for v in obj.data.vertices) for d in range(3)]
lat_data = bpy.data.lattices.new("frame")
lat_data.points_u = lat_data.points_v = lat_data.points_w = 5
for a in ("u", "v", "w"):
    setattr(lat_data, "interpolation_type_" + a, "KEY_BSPLINE")
lat = bpy.data.objects.new("frame", lat_data)
bpy.context.scene.collection.objects.link(lat)
lat.location = [(lo[d] + hi[d]) / 2 for d in range(3)]
lat.scale = [hi[d] - lo[d] for d in range(3)]
for p in lat_data.points:  # lattice coordinates in [-0.5, 0.5]
    x, y, z = p.co
    s = 0.6 + 0.4 * (2 * z) ** 2  # narrow waist, as the spool
    p.co_deform = (x * s, y * s, z)
mod = obj.modifiers.new("lattice", "LATTICE")
mod.object = lat

def evaluate(show):
    mod.show_viewport = show
    dg = bpy.context.evaluated_depsgraph_get()
    dg.update()
    obj.update_tag(refresh={"DATA"})
    t0 = time.perf_counter()
    dg.update()
    me = obj.evaluated_get(dg).to_mesh()
    n = len(me.vertices)
    t1 = time.perf_counter()
    obj.evaluated_get(dg).to_mesh_clear()
    return t1 - t0, n

# REPEAT 0: the whole process only (import, deform, export), untimed inside
with_mod = min([evaluate(True)[0] for _ in range(repeat)] or [0.0])
without = min([evaluate(False)[0] for _ in range(repeat)] or [0.0])
mod.show_viewport = True
nverts = len(obj.data.vertices)
bpy.ops.object.select_all(action="DESELECT")
obj.select_set(True)
bpy.context.view_layer.objects.active = obj
t_export0 = time.perf_counter()
bpy.ops.export_mesh.stl(filepath=dst, use_selection=True, use_mesh_modifiers=True, ascii=False)
t_end = time.perf_counter()
print("BLENDER vertices %d modifier %.6f with %.6f without %.6f import %.6f export %.6f" %
      (nverts, with_mod - without, with_mod, without, t_import - t_start, t_end - t_export0))

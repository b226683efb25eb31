# flockpath export: run inside Blender (Scripting workspace)
import bpy

scene = bpy.context.scene
scene.render.fps = 30
scene.frame_start = 1
scene.frame_end = 7

GROUPS = [
    ("flock", (0.1843, 0.4353, 0.8745, 1.0)),
    ("second", (0.8745, 0.4353, 0.1843, 1.0)),
]

# Per agent: (group index, [(frame, x, y), ...])
AGENTS = [
    (0, [(1, 59.50289, -129.56357), (2, 59.27178, -129.38017), (3, 59.338886, -129.2294), (4, 59.7042, -129.11139), (5, 60.367706, -129.02625), (6, 61.32939, -128.97412), (7, 62.58924, -128.95517), ]),
    (0, [(1, 21.291851, -141.95558), (2, 21.178469, -141.58809), (3, 21.365086, -141.22151), (4, 21.851702, -140.85599), (5, 22.638313, -140.49174), (6, 23.72492, -140.1291), (7, 25.11152, -139.76865), ]),
    (0, [(1, 36.368355, -102.97177), (2, 36.954605, -103.29616), (3, 37.839607, -103.59318), (4, 39.02333, -103.86255), (5, 40.505753, -104.103966), (6, 42.28684, -104.31714), (7, 44.277485, -104.510315), ]),
    (1, [(1, 55.321404, -152.91301), (2, 55.047504, -152.87592), (3, 55.073566, -152.83415), (4, 55.399593, -152.78775), (5, 56.025585, -152.73674), (6, 56.95154, -152.68117), (7, 58.177467, -152.62105), ]),
    (1, [(1, 57.711037, -93.925285), (2, 57.77766, -94.37736), (3, 58.142742, -94.799034), (4, 58.80624, -95.18994), (5, 59.76812, -95.549706), (6, 61.028336, -95.877945), (7, 62.586853, -96.174286), ]),
]

collections = []
for name, color in GROUPS:
    coll = bpy.data.collections.new("flockpath_" + name)
    scene.collection.children.link(coll)
    collections.append((coll, color))

for index, (group, keys) in enumerate(AGENTS):
    empty = bpy.data.objects.new("agent_%d" % index, None)
    empty.empty_display_type = "CONE"
    empty.empty_display_size = 0.05
    if collections:
        coll, color = collections[group]
        empty.color = color
        coll.objects.link(empty)
    else:
        scene.collection.objects.link(empty)
    for frame, x, y in keys:
        empty.location = (x, y, 0.0)
        empty.keyframe_insert(data_path="location", frame=frame)

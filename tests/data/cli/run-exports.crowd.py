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
    (0, [(1, 29.123734, -139.02808), (2, 29.211447, -139.46118), (3, 29.59184, -139.82843), (4, 30.264841, -140.12949), (5, 31.230371, -140.36401), (6, 32.488358, -140.53168), (7, 34.038723, -140.63216), ]),
    (0, [(1, 19.832624, -191.99207), (2, 19.791388, -191.5698), (3, 20.050148, -191.14894), (4, 20.608904, -190.72975), (5, 21.467651, -190.31259), (6, 22.626389, -189.89803), (7, 24.085104, -189.48708), ]),
    (0, [(1, 75.614136, -96.31683), (2, 75.52299, -96.69188), (3, 75.73136, -97.04986), (4, 76.23923, -97.390434), (5, 77.04656, -97.713295), (6, 78.15336, -98.018105), (7, 79.55959, -98.30454), ]),
    (1, [(1, 18.604633, -128.06094), (2, 18.972872, -127.58359), (3, 19.6411, -127.10884), (4, 20.60931, -126.63731), (5, 21.877491, -126.16998), (6, 23.445606, -125.70886), (7, 25.313396, -125.260735), ]),
    (1, [(1, 67.70067, -85.94228), (2, 68.062164, -85.55628), (3, 68.698845, -85.28975), (4, 69.61054, -85.14307), (5, 70.79709, -85.11662), (6, 72.258316, -85.21081), (7, 73.99405, -85.426), ]),
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

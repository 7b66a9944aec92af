"""The add-on's Blender-free layer: the native module, meshing jobs, colour maps and legend geometry.

Nothing here imports bpy, so all of it runs (and is tested) in any Python that has numpy.
"""

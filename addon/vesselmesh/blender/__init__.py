"""The add-on's Blender layer: meshes, materials, legend objects, settings, operators and the sidebar.
The work itself happens in ..core, which never imports bpy."""

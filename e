scene.lua: cannot read the scene file: No such file or directory

//! Software rasterizer for triangle meshes (z-buffer, flat and smooth shading). TODO(helper).

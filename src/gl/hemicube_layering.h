// How the GPU's layered hemicubes (layered_hemicubes.h) route each triangle to its layer, apart
// from the GL class so that solver settings can name it without OpenGL.
#pragma once

namespace luxel::gl {

// GeometryShader: core OpenGL 4.5. VertexShader: ARB_shader_viewport_layer_array, which spares a
// GPU the geometry stage that every triangle of every layer passes. Auto: the second where the
// driver has it.
enum class HemicubeLayering { Auto, GeometryShader, VertexShader };

}  // namespace luxel::gl

// The Cryptomatte layers --passes asks for (core/film/cryptomatte.h), with the names of the scene
// the render's geometry was built from, indexed as RenderGeometry::SurfaceIdentity indexes them.
#pragma once

#include <string>
#include <vector>

#include "core/film/cryptomatte.h"
#include "core/scene/scene.h"

namespace fb {

// CryptoObject: each instance's node name (glTF's node name, or its JSON path when it has none;
// the primitives and GPU instances of one node share it, as Blender's object does), then each
// solid's name; CryptoAsset: the same, each instance named by its node tree's root instead
// (Scene::assets); CryptoMaterial: each material's name. In the order `passes` names them; empty
// when it names none.
std::vector<CryptomatteLayer> cryptomatte_layers(const Scene& scene,
                                                 const std::vector<std::string>& passes);

}  // namespace fb

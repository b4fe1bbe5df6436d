"""A Blender light as the node's FILMBACK_blender light, in Blender's own units.

The properties are bpy 3.4's (checked against Blender 3.4.1): `shadow_soft_size` is the Radius of
point and spot lights, `spot_size` the full cone angle, `angle` the sun's angular diameter,
`shape`/`size`/`size_y` the area light's (`size_y` counts for RECTANGLE and ELLIPSE only), and
`spread` the area light's Spread (radians, 180 degrees by default)."""


def light_extension(light):
    out = {"type": light.type, "color": list(light.color), "energy_w": light.energy,
           "use_nodes": bool(light.use_nodes)}
    if light.type in ("POINT", "SPOT"):
        out["radius_m"] = light.shadow_soft_size
    if light.type == "SPOT":
        out["spot_size_rad"] = light.spot_size
        out["spot_blend"] = light.spot_blend
    elif light.type == "SUN":
        out["angle_rad"] = light.angle
    elif light.type == "AREA":
        out["shape"] = light.shape
        out["size_m"] = light.size
        out["size_y_m"] = light.size_y
        out["spread_rad"] = light.spread
    return out

"""Where a node input's value comes from, as Cycles 3.4 connects a Blender node tree.

Cycles (intern/cycles/blender/shader.cpp, `add_nodes`) replaces reroutes and muted nodes by their
internal links, inlines node groups through proxies keyed by socket identifier (only the active
Group Output counts), and drops links that are invalid, muted or touch a disabled socket. `source`
walks a link chain the same way and returns what feeds an input: a real node's output socket, or
a constant (an unlinked socket's value, or an RGB or Value node's).

A position in a tree is a socket plus its group path: the tuple of Group nodes, outermost first,
whose trees contain it (the same node inside two instances of a group is two different nodes).
"""

# Links followed from one input, at most: node trees are acyclic (Blender marks a link that
# closes a cycle invalid, and those are skipped), so this bounds only pathological group nesting.
MAX_HOPS = 4096

# Scene-linear luminance weights of Blender 3.4's OCIO config (`luma` in
# datafiles/colormanagement/config.ocio), which Cycles' colour-to-float conversion uses
# (`linear_rgb_to_gray`).
LUMA = (0.2126, 0.7152, 0.0722)


class Output:
    """A real node's output socket feeds the input. `narrowed`: the output is a colour or vector
    that crossed a float socket on the way (Cycles took its luminance or average there)."""

    def __init__(self, socket, path, narrowed):
        self.socket, self.node, self.path, self.narrowed = socket, socket.node, path, narrowed


class Constant:
    """The input takes a constant: `value` (a float or a list of floats, in the input's type)."""

    def __init__(self, value):
        self.value = value


def active_link(socket):
    """The link Cycles uses into `socket`, or None."""
    for link in socket.links:
        if link.is_valid and not link.is_muted and link.from_socket.enabled and \
                link.to_socket.enabled:
            return link
    return None


def socket_value(socket):
    """A socket's own value: a float, or [r, g, b] / [x, y, z] (colours drop their alpha); None
    for a shader socket."""
    if socket.type == "SHADER":
        return None
    value = socket.default_value
    if socket.type == "RGBA":
        return list(value)[:3]
    if socket.type == "VECTOR":
        return list(value)
    return float(value)


def convert(value, from_type, to_type):
    """A constant across a link between socket types, as Cycles' ConvertNode folds it: colour to
    float is the luminance, vector to float the average, float to colour or vector a grey."""
    if from_type == to_type or to_type not in ("VALUE", "RGBA", "VECTOR"):
        return value
    if to_type == "VALUE":
        if from_type == "RGBA":
            return sum(w * c for w, c in zip(LUMA, value))
        if from_type == "VECTOR":
            return sum(value) / 3.0
        return float(value)
    if from_type in ("VALUE", "INT", "BOOLEAN"):
        return [float(value)] * 3
    return list(value)


def zero(socket_type):
    """What an unfed socket of this type holds in Cycles: 0, black, or no closure (None)."""
    if socket_type == "SHADER":
        return None
    return 0.0 if socket_type == "VALUE" else [0.0, 0.0, 0.0]


def _group_output(tree):
    return next((n for n in tree.nodes if n.type == "GROUP_OUTPUT" and n.is_active_output), None)


def _by_identifier(sockets, identifier):
    return next((s for s in sockets if s.identifier == identifier), None)


def source(socket, path):
    """What feeds `socket` (an input at group path `path`): an Output, or a Constant in the
    input's own type."""
    target = socket
    chain = [socket.type]  # socket types from the target back to the source
    for _ in range(MAX_HOPS):
        link = active_link(socket)
        if link is None:
            value = socket_value(socket) if socket.enabled else zero(socket.type)
            return Constant(_convert_back(value, chain))
        out = link.from_socket
        node = out.node
        chain.append(out.type)
        if node.type == "REROUTE" or node.mute:
            through = next((l for l in node.internal_links if l.to_socket == out), None)
            if through is None:
                # Nothing passes: Cycles leaves the input unconnected, at its own value.
                return Constant(socket_value(target))
            socket = through.from_socket
            chain.append(socket.type)
            if active_link(socket) is None:
                # Cycles' proxy (a ConvertNode) for a reroute or muted node keeps its zero value
                # when nothing feeds it: `add_nodes` never sets its input from the socket.
                return Constant(_convert_back(zero(socket.type), chain))
            continue
        if node.type == "GROUP":
            inner = _group_output(node.node_tree) if node.node_tree is not None else None
            inner_socket = _by_identifier(inner.inputs, out.identifier) if inner else None
            if inner_socket is None:
                return Constant(_convert_back(zero(out.type), chain))  # an unfed proxy
            socket, path = inner_socket, path + (node,)
            chain.append(socket.type)
            continue
        if node.type == "GROUP_INPUT":
            outer = _by_identifier(path[-1].inputs, out.identifier) if path else None
            if outer is None:
                return Constant(_convert_back(zero(out.type), chain))
            socket, path = outer, path[:-1]
            chain.append(socket.type)
            continue
        if node.type in ("RGB", "VALUE"):
            return Constant(_convert_back(socket_value(out), chain))  # Cycles' constant nodes
        narrowed = out.type != "VALUE" and "VALUE" in chain[1:-1]
        return Output(out, path, narrowed)
    raise ValueError(f"node link chain into '{target.node.name}' is longer than {MAX_HOPS} links")


def _convert_back(value, chain):
    """`value`, held by the socket at the end of `chain`, as the target (chain[0]) receives it:
    converted at every change of type along the chain."""
    for from_type, to_type in zip(reversed(chain[1:]), reversed(chain[:-1])):
        value = convert(value, from_type, to_type)
    return value

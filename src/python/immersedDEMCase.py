"""Read a case's physical constants from its OpenFOAM dictionaries, so that
plot and check scripts take them from the case they check, never from a
number written in the script:

    from immersedDEMCase import caseConstants
    c = caseConstants("path/to/case")
    c.rhoFluid          # rhoInf of the immersedDEM function object [kg/m3]
    c.nu                # its nu, else constant/transportProperties' [m2/s]
    c.g, c.gravity      # constant/g: the vector, and its magnitude [m/s2]
    c.density("cubes_3")  # a body's density: bodies/<name>, or the template
                          # of the insertion block whose name prefixes it
    c.bodyEntry("cubes_3")  # that dictionary (file, scale, ...)
    c.meshBounds()      # system/blockMeshDict's vertices' box [m]

readDictionary(path) parses an OpenFOAM dictionary into nested Python
dicts: a value of one word is a string, of several a list of them, a
'( ... )' a list; '$name' (an entry, or a sub-dictionary merged in) is
looked up in the enclosing dictionaries; '#include "file"' (and
#includeIfPresent) reads the file beside it, other '#' directives are
skipped with their argument. number(value) is a scalar value's number,
the last word of a dimensioned one ('nu [0 2 -1 0 0 0 0] 1e-6').
"""
import math
import os
import re


class dictionaryError(ValueError):
    pass


def _tokens(text, path):
    # Comments out, then words, brackets and ';'
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", " ", text)
    for m in re.finditer(r'"[^"]*"|[{}();\[\]]|[^\s{}();\[\]"]+', text):
        yield m.group(0)


def _list(tokens, scopes, path):
    out = []
    for t in tokens:
        if t == ")":
            return out
        if t == "(":
            out.append(_list(tokens, scopes, path))
        elif t == "{":
            out.append(_dictionary(tokens, scopes, path, True))
        elif t.startswith("$") and any(t[1:] in s for s in scopes):
            out.append(_copy(_lookup(scopes, t[1:], path)))
        else:
            out.append(t)
    raise dictionaryError("%s: a '(' is not closed" % path)


def _lookup(scopes, name, path):
    for s in reversed(scopes):
        if name in s:
            return s[name]
    raise dictionaryError("%s: '$%s' names no entry" % (path, name))


def _copy(v):
    if isinstance(v, dict):
        return {k: _copy(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_copy(x) for x in v]
    return v


def _dictionary(tokens, scopes, path, closing):
    d = {}
    scopes = scopes + [d]
    while True:
        t = next(tokens, None)
        if t is None:
            if closing:
                raise dictionaryError("%s: a '{' is not closed" % path)
            return d
        if t == "}":
            if not closing:
                raise dictionaryError("%s: a '}' closes nothing" % path)
            return d
        if t.startswith("#"):
            # #include "file" (and #includeIfPresent) beside this file:
            # its entries here; other directives (#includeEtc,
            # #includeFunc, #inputMode) skipped with their argument
            arg = (next(tokens, None) or "").strip('"')
            if t in ("#include", "#includeIfPresent"):
                q = os.path.join(os.path.dirname(path), arg)
                if os.path.isfile(q) or t == "#include":
                    d.update(_dictionary(_tokens(_read(q), q), scopes, q, False))
            continue
        if t.startswith("$"):
            # '$name;': the entries of the named dictionary, here
            v = _lookup(scopes, t[1:], path)
            if not isinstance(v, dict):
                raise dictionaryError("%s: '%s;' is not a dictionary" % (path, t))
            d.update(_copy(v))
            if next(tokens, None) != ";":
                raise dictionaryError("%s: '%s' without ';'" % (path, t))
            continue
        key = t.strip('"')
        words = []
        while True:
            u = next(tokens, None)
            if u is None:
                raise dictionaryError("%s: entry '%s' has no ';'" % (path, key))
            if u == "{" and not words:
                d[key] = _dictionary(tokens, scopes, path, True)
                break
            if u == ";":
                d[key] = words[0] if len(words) == 1 else words
                break
            if u == "(":
                words.append(_list(tokens, scopes, path))
            elif u == "[":
                dims = []
                for w in tokens:
                    if w == "]":
                        break
                    dims.append(w)
                words.append("[" + " ".join(dims) + "]")
            elif u.startswith("$"):
                words.append(_copy(_lookup(scopes, u[1:], path)))
            else:
                words.append(u)


def _read(path):
    try:
        return open(path).read()
    except OSError as e:
        raise dictionaryError("cannot read %s: %s" % (path, e))


def readDictionary(path):
    """The dictionary in the file at path (FoamFile header included)."""
    return _dictionary(_tokens(_read(path), path), [], path, False)


def number(value):
    """The number of a scalar entry: '1e-6', or the last word of
    'nu [0 2 -1 0 0 0 0] 1e-6' (or of ['nu', '[...]', '1e-6'])."""
    if isinstance(value, list):
        value = value[-1]
    try:
        return float(value)
    except (TypeError, ValueError):
        raise dictionaryError("'%s' is not a number" % (value,))


def vector(value):
    if isinstance(value, list) and len(value) == 1:
        value = value[0]
    if not (isinstance(value, list) and len(value) == 3):
        raise dictionaryError("'%s' is not a vector" % (value,))
    return tuple(float(x) for x in value)


class caseConstants:
    """The fluid's density and viscosity, gravity, the bodies' densities and
    the mesh's box of one case, each read when first asked."""

    def __init__(self, case="."):
        self.case = case
        self._dicts = {}

    def dictionary(self, *relative):
        p = os.path.join(self.case, *relative)
        if p not in self._dicts:
            self._dicts[p] = readDictionary(p)
        return self._dicts[p]

    def _get(self, d, key, where):
        if key not in d:
            raise dictionaryError("no '%s' in %s" % (key, where))
        return d[key]

    def functionObject(self):
        """The immersedDEM function object's dictionary (system/controlDict)."""
        cd = self.dictionary("system", "controlDict")
        found = [f for f in cd.get("functions", {}).values()
                 if isinstance(f, dict) and f.get("type") == "immersedDEM"]
        if len(found) != 1:
            raise dictionaryError("%s/system/controlDict: %d immersedDEM function objects, not one"
                                  % (self.case, len(found)))
        return found[0]

    @property
    def rhoFluid(self):
        return number(self._get(self.functionObject(), "rhoInf", "the immersedDEM function object"))

    @property
    def nu(self):
        # As the function object: its own nu, else the solver's
        fo = self.functionObject()
        if "nu" in fo:
            return number(fo["nu"])
        p = os.path.join("constant", "transportProperties")
        return number(self._get(self.dictionary(p), "nu", os.path.join(self.case, p)))

    @property
    def g(self):
        p = os.path.join("constant", "g")
        return vector(self._get(self.dictionary(p), "value", os.path.join(self.case, p)))

    @property
    def gravity(self):
        return math.sqrt(sum(x*x for x in self.g))

    def bodyEntry(self, body):
        """The dictionary that makes a body: bodies/<body>, or the template
        of the insertion block whose name and '_' begin the body's name."""
        p = os.path.join(self.case, "constant", "immersedDEMProperties")
        d = self.dictionary("constant", "immersedDEMProperties")
        bodies = d.get("bodies", {})
        if body in bodies:
            return bodies[body]
        for name, block in d.get("insertion", {}).items():
            if isinstance(block, dict) and body.startswith(name + "_"):
                t = self._get(block, "template", "%s: insertion/%s" % (p, name))
                templates = d.get("templates", {})
                if t not in templates:
                    raise dictionaryError("%s: insertion/%s names template %s, not in templates" % (p, name, t))
                return templates[t]
        raise dictionaryError("%s: no body or insertion block gives body %s" % (p, body))

    def density(self, body):
        """A body's density (bodyEntry's)."""
        return number(self._get(self.bodyEntry(body), "density",
                                "constant/immersedDEMProperties' entry of body %s" % body))

    def meshBounds(self):
        """The box of system/blockMeshDict's vertices, scaled [m]."""
        p = os.path.join("system", "blockMeshDict")
        d = self.dictionary(p)
        scale = number(d.get("scale", d.get("convertToMeters", "1")))
        pts = [vector(v) for v in self._get(d, "vertices", os.path.join(self.case, p))]
        lo = tuple(scale*min(v[k] for v in pts) for k in range(3))
        hi = tuple(scale*max(v[k] for v in pts) for k in range(3))
        return lo, hi

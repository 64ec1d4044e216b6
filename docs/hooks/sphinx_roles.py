"""Griffe extension: the Sphinx roles of the numpydoc docstrings as API-reference links.

The docstrings name other objects the Sphinx way (:func:`ga_rotors.scene.run_scene`,
:class:`~ga_rotors.trajectory.Trajectory`, :mod:`ga_rotors.view`, :meth:`.replace`),
which Markdown would show as raw text. Once the package is loaded, each role is looked up
where Sphinx would look (the object's class, its module and the modules above it, then
the name as written) and rewritten as an autorefs cross-reference in code type:

* a target this package defines becomes an *optional* reference: a link when the target
  is rendered on some page of the site, plain code text when it is not (a private helper,
  a module the reference does not show);
* a target outside the package (``numpy.ndarray``, ``scipy.integrate.quad``) is code text:
  the site is built offline, with no other project's inventory;
* a name written unqualified, as users write them (:meth:`append` in a module's
  docstring, :meth:`check_step` in a method inherited from a base class), is looked up
  among the members of the current class, its bases, then the classes of the current
  module: found once, it links; found in several classes (each writer's ``append``), it
  is code text, since no single entry is meant;
* a ``ga_rotors`` name that does not exist at all is a mistake in a docstring: it is
  logged as a warning, which fails ``mkdocs build --strict``, and shown as code text.

Mathematics is written the numpydoc way, :math:`\\tilde R` inline and a ``.. math::``
directive followed by an indented block for a displayed formula (LaTeX, as in numpy's and
scipy's docstrings). Both become the ``$...$`` and ``$$...$$`` of the site's Markdown, which
docs/hooks/mathml.py typesets as MathML.

Registered in mkdocs.yml under the python handler's ``extensions``.
"""

from __future__ import annotations

import builtins
import html
import importlib
import re
import types

import griffe

ROLE = re.compile(
    r":(?:py:)?(?P<role>mod|func|class|data|meth|attr|obj|exc|const|attribute|function)"
    r":`(?P<body>[^`\n]+)`"
)
#: The inline formula role; its body is LaTeX.
MATH_ROLE = re.compile(r":math:`(?P<tex>[^`]+)`")
#: The directive of a displayed formula; its body is the indented block that follows.
MATH_DIRECTIVE = re.compile(r"(?P<indent>[ \t]*)\.\. math::[ \t]*")
#: Roles whose target Sphinx shows with call parentheses.
CALLABLE = {"func", "meth", "function"}
ATTRIBUTE = {"attr", "attribute", "data"}
PACKAGE = "ga_rotors"

_log = griffe.logger


class SphinxRoles(griffe.Extension):
    """Rewrite :role:`target` in every docstring of a loaded package (see the module)."""

    def on_package(self, *, pkg: griffe.Module, loader: griffe.GriffeLoader, **kwargs) -> None:
        if pkg.path != PACKAGE:
            return
        for obj in _walk(pkg):
            if obj.docstring is None:
                continue
            text = typeset_math(obj.docstring.value)
            if ROLE.search(text):
                text = ROLE.sub(lambda m, obj=obj: _reference(m, obj, loader), text)
            obj.docstring.value = text


def typeset_math(docstring: str) -> str:
    """``docstring`` with its :math:`...` roles and ``.. math::`` blocks in the site's
    Markdown: ``$...$`` inline, a displayed formula between two ``$$`` lines."""
    docstring = MATH_ROLE.sub(lambda m: f"${m['tex'].strip()}$", docstring)
    lines, out = docstring.splitlines(), []
    i = 0
    while i < len(lines):
        directive = MATH_DIRECTIVE.fullmatch(lines[i])
        i += 1
        if directive is None:
            out.append(lines[i - 1])
            continue
        indent, body = directive["indent"], []
        while i < len(lines) and (
            not lines[i].strip() or len(lines[i]) - len(lines[i].lstrip()) > len(indent)
        ):
            body.append(lines[i])
            i += 1
        while body and not body[-1].strip():  # blank lines after the block stay after it
            body.pop()
            i -= 1
        text = [x for x in body if x.strip()]
        depth = min((len(x) - len(x.lstrip()) for x in text), default=0)
        if out and out[-1].strip():
            out.append("")
        out += [f"{indent}$$", *(f"{indent}{x[depth:]}" for x in text), f"{indent}$$"]
    return "\n".join(out) + ("\n" if docstring.endswith("\n") else "")


def _walk(obj: griffe.Object):
    yield obj
    for member in obj.members.values():
        if member.is_alias:  # documented where it is defined
            continue
        yield from _walk(member)


def _split(body: str) -> tuple[str | None, str, bool]:
    """(explicit title or None, target, short) from a role's body."""
    title = None
    found = re.fullmatch(r"(?P<title>.*?)\s*<(?P<target>[^<>]+)>", body)
    if found:
        title, body = found["title"], found["target"]
    body = body.lstrip("!")
    short = body.startswith("~")
    return title, body.lstrip("~"), short


def _candidates(target: str, obj: griffe.Object):
    """Where Sphinx would look for ``target`` written in ``obj``'s docstring."""
    name = target.lstrip(".")
    scopes = []
    scope = obj if obj.is_class or obj.is_module else obj.parent
    while scope is not None:
        scopes.append(scope.path)
        scope = scope.parent
    if target.startswith("."):  # Sphinx's ".name": any object ending with it, nearest first
        yield from (f"{s}.{name}" for s in scopes)
    else:
        yield name
        yield from (f"{s}.{name}" for s in scopes)


def _lookup(path: str, loader: griffe.GriffeLoader) -> griffe.Object | griffe.Alias | None:
    try:
        return loader.modules_collection.get_member(path)
    except (KeyError, ValueError, griffe.AliasResolutionError, griffe.CyclicAliasError):
        pass
    defined = _defined_at(path)
    if defined is None or defined == path:
        return None
    return _lookup(defined, loader)


def _defined_at(path: str) -> str | None:
    """Where the object imported as ``path`` is defined, asking Python itself.

    The package's ``__init__`` modules export their names lazily (a module
    ``__getattr__``), which a static reading cannot follow; the build imports the
    package anyway (the examples run), so importing it here costs nothing new.
    """
    parts = path.split(".")
    if parts[0] != PACKAGE:
        return None
    for i in range(len(parts), 0, -1):
        try:
            value = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        where = value.__name__
        for name in parts[i:]:
            try:
                value = getattr(value, name)
            except AttributeError:
                return None
            module, qualname = (
                getattr(value, "__module__", None),
                getattr(value, "__qualname__", None),
            )
            if isinstance(value, types.ModuleType):
                where = value.__name__
            elif isinstance(module, str) and isinstance(qualname, str):
                where = f"{module}.{qualname}"
            else:  # a property or a value: named after its owner
                where = f"{where}.{name}"
        return where
    return None


def _instance_attribute(path: str, loader: griffe.GriffeLoader) -> str | None:
    """The full path of ``Class.name`` when the class's code assigns ``self.name`` (an
    attribute set by tuple unpacking is invisible to the static reading), else None."""
    owner, _, name = path.rpartition(".")
    cls = _lookup(owner, loader)
    try:
        cls = cls.final_target if cls is not None and cls.is_alias else cls
    except (griffe.AliasResolutionError, griffe.CyclicAliasError):
        return None
    if cls is None or not cls.is_class:
        return None
    if re.search(rf"\bself\.{re.escape(name)}\b(?!\s*\()", cls.source) is None:
        return None
    return f"{cls.path}.{name}"


def _unqualified(name: str, obj: griffe.Object) -> list[str]:
    """The paths of the members called ``name`` that an unqualified role in ``obj``'s
    docstring can mean: in the enclosing class or its bases if one has it, else in any
    class of the enclosing module (each class counted once, inherited members included)."""
    scope = obj
    while scope is not None and not (scope.is_class or scope.is_module):
        scope = scope.parent
    cls = scope if scope is not None and scope.is_class else None
    module = obj if obj.is_module else obj.module

    def member(owner: griffe.Object) -> str | None:
        try:
            found = owner.all_members.get(name)
            if found is None:
                return None
            return found.final_target.path if found.is_alias else found.path
        except (griffe.AliasResolutionError, griffe.CyclicAliasError):
            return None

    if cls is not None and (path := member(cls)) is not None:
        return [path]
    paths = []
    for owner in module.classes.values():
        if owner.is_alias or owner.name.startswith("_"):
            continue
        path = member(owner)
        if path is not None:
            paths.append(path)
    return paths


def _reference(match: re.Match, obj: griffe.Object, loader: griffe.GriffeLoader) -> str:
    role = match["role"]
    title, target, short = _split(match["body"])
    if title is None:
        title = target.lstrip(".").rsplit(".", 1)[-1] if short else target.lstrip(".")
        if role in CALLABLE and not title.endswith(")"):
            title += "()"
    code = f"<code>{html.escape(title)}</code>"
    for path in _candidates(target, obj):
        found = _lookup(path, loader)
        if found is not None:
            try:
                path = found.final_target.path if found.is_alias else found.path
            except (griffe.AliasResolutionError, griffe.CyclicAliasError):
                return code  # an import from another package
            if path != PACKAGE and not path.startswith(PACKAGE + "."):
                return code
            return f'<autoref identifier="{html.escape(path)}" optional>{code}</autoref>'
        attribute = _instance_attribute(path, loader) if role in ATTRIBUTE else None
        if attribute is not None:
            return f'<autoref identifier="{html.escape(attribute)}" optional>{code}</autoref>'
    if "." not in target.lstrip("."):
        members = _unqualified(target.lstrip("."), obj)
        if len(members) == 1:
            return f'<autoref identifier="{html.escape(members[0])}" optional>{code}</autoref>'
        if members:
            _log.debug(f"{obj.path}: {match[0]}: a member of {len(members)} classes, shown as code")
            return code
    ours = target.split(".")[0] == PACKAGE or target.startswith(".")
    if ours or ("." not in target and not hasattr(builtins, target)):
        where = f"{obj.relative_filepath}:{obj.docstring.lineno}"
        _log.warning(f"{where}: {match[0]}: no such object seen from {obj.path}")
    else:
        _log.debug(f"{obj.path}: {match[0]}: outside {PACKAGE}, shown as code")
    return code

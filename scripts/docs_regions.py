"""The one way the docs scripts rewrite a generated table: the text between `<!-- generated: NAME -->` and
`<!-- end -->` in a Markdown file is replaced, the text around it is left alone."""
import re
import sys


def replace(path, regions):
    """Rewrites each region NAME of `path` with its body (a string, or a list of lines); exits if one is missing."""
    with open(path) as f:
        text = f.read()
    for name, body in regions.items():
        pattern = re.compile(r"(<!-- generated: " + re.escape(name) + r" -->\n).*?(<!-- end -->)", re.S)
        if not pattern.search(text):
            sys.exit(f"{path}: no region '{name}'")
        body = body if isinstance(body, str) else "\n".join(body)
        text = pattern.sub(lambda m: m.group(1) + body + "\n" + m.group(2), text, count=1)
    with open(path, "w") as f:
        f.write(text)
    print(f"{path}: {', '.join(regions)}", file=sys.stderr)

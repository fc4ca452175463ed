"""Read immersedDEM's tables (bodies.dat, contacts.dat) by column name.

Both are whitespace tables with a '#' header line of column names (see
caseTemplates/README.md, "Outputs"). Every script and plot of the project
reads them through this module, never by column position:

    from immersedDEMData import readTable
    t = readTable("postProcessing/bodies/0/bodies.dat")
    ball = t.where(body="ball")
    ball["time"], ball["vz"]            # lists of floats
    ball.last("z")                      # the last row's value

Text columns (body, bodyA, bodyB) stay strings; every other column is a
float. A row whose length differs from the header's (a file being written)
is skipped.
"""
import os

TEXT_COLUMNS = {"body", "bodyA", "bodyB"}


class Table:
    def __init__(self, columns, rows, path=""):
        self.columns = list(columns)
        self.rows = rows
        self.path = path
        self._index = {c: i for i, c in enumerate(self.columns)}

    def __len__(self):
        return len(self.rows)

    def __contains__(self, column):
        return column in self._index

    def index(self, column):
        try:
            return self._index[column]
        except KeyError:
            raise KeyError("%s has no column '%s' (columns: %s)"
                           % (self.path or "the table", column, " ".join(self.columns)))

    def __getitem__(self, column):
        """All values of a column, in row order."""
        i = self.index(column)
        return [r[i] for r in self.rows]

    def where(self, **match):
        """The rows whose columns equal the given values (e.g. body="ball")."""
        idx = [(self.index(c), v) for c, v in match.items()]
        return Table(self.columns, [r for r in self.rows if all(r[i] == v for i, v in idx)],
                     self.path)

    def last(self, column):
        if not self.rows:
            raise ValueError("%s has no rows" % (self.path or "the table"))
        return self.rows[-1][self.index(column)]

    def bodies(self):
        """The body names in order of first appearance."""
        seen = []
        for b in self["body"]:
            if b not in seen:
                seen.append(b)
        return seen


def _value(column, text):
    return text if column in TEXT_COLUMNS else float(text)


def readTable(path):
    """A bodies.dat or contacts.dat (or any table with a '#' header)."""
    columns = None
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                if columns is None:
                    columns = line[1:].split()
                continue
            fields = line.split()
            if columns is None or len(fields) != len(columns):
                continue
            rows.append([_value(c, x) for c, x in zip(columns, fields)])
    if columns is None:
        raise ValueError("%s has no '#' header line of column names" % path)
    return Table(columns, rows, path)


def readOutputs(directory):
    """bodies.dat and contacts.dat of one output folder
    (postProcessing/<name>/<startTime>); contacts is None if absent."""
    bodies = readTable(os.path.join(directory, "bodies.dat"))
    c = os.path.join(directory, "contacts.dat")
    return bodies, (readTable(c) if os.path.exists(c) else None)

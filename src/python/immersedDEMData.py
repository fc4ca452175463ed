"""Read immersedDEM's tables (bodies.dat, contacts.dat) by column name.

Both are whitespace tables with a '#' header line of column names (see
caseTemplates/README.md, "Outputs"). Every script and plot of the project
reads them through this module, never by column position:

    from immersedDEMData import readTable
    t = readTable("postProcessing/bodies/0/bodies.dat")
    ball = t.where(body="ball")
    ball["time"], ball["vz"]            # lists of floats
    ball.last("z")                      # the last row's value

readRuns("postProcessing/bodies") joins the tables of every run of a case
(restarts, reruns) in time order.

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


def readRuns(directory, name="bodies"):
    """One function object's tables of every run of a case, in time order:
    <name>.dat of each start-time folder under directory
    (postProcessing/<function object>/<start>/) and <name>_<start>.dat of a
    rerun from the same start time. Where runs overlap in time the later
    run's rows are kept (a restart from an earlier time replaces the rows
    after it). Runs whose columns differ (a restart of a case written by
    an older version, before columns were added) are joined on the columns
    they share, in the first run's order. Raises ValueError if there is
    none, or if they share no time column."""
    files = []
    if os.path.isdir(directory):
        for start in os.listdir(directory):
            d = os.path.join(directory, start)
            if not os.path.isdir(d):
                continue
            for f in os.listdir(d):
                if f == name + ".dat" or (f.startswith(name + "_") and f.endswith(".dat")):
                    files.append(os.path.join(d, f))
    if not files:
        raise ValueError("no %s.dat under %s: run the case first" % (name, directory))
    tables = [readTable(f) for f in files]
    tables.sort(key=lambda t: t.rows[0][t.index("time")] if len(t) else float("inf"))
    columns = [c for c in tables[0].columns if all(c in t for t in tables)]
    if "time" not in columns:
        raise ValueError("the tables under %s share no 'time' column" % directory)
    rows = []
    i = columns.index("time")
    for t in tables:
        if len(t):
            idx = [t.index(c) for c in columns]
            start = t.rows[0][t.index("time")]
            rows = [r for r in rows if r[i] < start] + [[r[k] for k in idx] for r in t.rows]
    return Table(columns, rows, directory)

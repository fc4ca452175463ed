"""Drop the last facet of an ASCII STL (makes a hole) in place."""
import re
import sys

path = sys.argv[1]
text = open(path).read()
facets = re.findall(r' facet.*?endfacet\n', text, re.S)
open(path, 'w').write('solid block\n' + ''.join(facets[:-1]) + 'endsolid block\n')

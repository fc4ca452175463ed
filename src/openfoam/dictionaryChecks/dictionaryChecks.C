#include "dictionaryChecks.H"
#include "Time.H"
#include "IOstreams.H"
#include "IFstream.H"
#include "OSspecific.H"

namespace
{

using namespace Foam;

// Skips the rest of a statement whose first token after the keyword was
// already read as t: up to the ';' outside brackets, or over a block
void skipStatement(Istream& is, token t)
{
    label depth = 0;
    while (t.good())
    {
        if (t.isPunctuation())
        {
            const token::punctuationToken p = t.pToken();
            if (p == token::BEGIN_LIST || p == token::BEGIN_BLOCK || p == token::BEGIN_SQR)
            {
                ++depth;
            }
            else if (p == token::END_LIST || p == token::END_BLOCK || p == token::END_SQR)
            {
                if (--depth < 0) { is.putBack(t); return; }
            }
            else if (p == token::END_STATEMENT && depth == 0)
            {
                return;
            }
        }
        is.read(t);
    }
}


void scanScope
(
    Istream& is,
    const fileName& file,
    const std::string& scope,
    const std::map<std::string, std::string>& what,
    std::map<std::string, label>& lines
)
{
    std::map<std::string, label> seen;
    token t;
    while (true)
    {
        is.read(t);
        if (!t.good())
        {
            return;
        }
        if (t.isPunctuation())
        {
            if (t.pToken() == token::END_BLOCK) return;
            continue;
        }
        std::string key;
        if (t.isWord())
        {
            key = t.wordToken();
        }
        else if (t.isString() && !t.isVariable())
        {
            key = t.stringToken();
        }
        else
        {
            // $variable expansions and stray values
            token next(is);
            skipStatement(is, next);
            continue;
        }
        const label line = t.lineNumber();
        if (key.size() && key[0] == '#')
        {
            // A directive (#include "file", #inputMode merge, #remove (a b)):
            // one argument
            token arg(is);
            if (arg.isPunctuation() && arg.pToken() == token::BEGIN_LIST)
            {
                skipStatement(is, arg);
            }
            continue;
        }
        const auto it = seen.find(key);
        if (it != seen.end())
        {
            const auto names = what.find(scope);
            const std::string where = scope.empty() ? "the top level" : "'" + scope + "'";
            std::string text;
            if (names != what.end())
            {
                text = "Two " + names->second + " named '" + key + "' in " + where;
            }
            else
            {
                text = "Keyword '" + key + "' appears twice in " + where;
            }
            FatalIOErrorInFunction(is)
                << text.c_str() << " of " << file << ": lines " << it->second
                << " and " << line << nl
                << "OpenFOAM would merge the two or keep the last silently:"
                << " give each " << (names != what.end() ? "a unique name" : "keyword once")
                << nl << exit(FatalIOError);
        }
        seen.emplace(key, line);
        const std::string path = scope.empty() ? key : scope + "/" + key;
        lines.emplace(path, line);
        token next(is);
        if (next.isPunctuation() && next.pToken() == token::BEGIN_BLOCK)
        {
            scanScope(is, file, path, what, lines);
        }
        else
        {
            skipStatement(is, next);
        }
    }
}

} // End anonymous namespace


std::map<std::string, Foam::label> Foam::immersedDEMChecks::noDuplicateKeywords
(
    const fileName& file,
    const std::map<std::string, std::string>& what
)
{
    std::map<std::string, label> lines;
    if (!isFile(file))
    {
        return lines;
    }
    IFstream is(file);
    if (!is.good())
    {
        return lines;
    }
    scanScope(is, file, "", what, lines);
    return lines;
}


void Foam::immersedDEMChecks::allowOnly(const dictionary& dict, const wordList& allowed)
{
    for (const entry& e : dict)
    {
        if (!allowed.found(e.keyword()))
        {
            FatalIOErrorInFunction(dict)
                << "Unknown keyword '" << e.keyword() << "' in "
                << dict.name() << nl
                << "Valid keywords: " << allowed << nl
                << exit(FatalIOError);
        }
    }
}


Foam::scalar Foam::immersedDEMChecks::positive
(
    const dictionary& dict,
    const word& key,
    bool zeroAllowed
)
{
    const scalar v = dict.get<scalar>(key);
    if (!(zeroAllowed ? v >= 0 : v > 0) || !std::isfinite(v))
    {
        FatalIOErrorInFunction(dict)
            << "Keyword '" << key << "' in " << dict.name() << " is " << v
            << "; it must be " << (zeroAllowed ? ">= 0" : "> 0") << nl
            << exit(FatalIOError);
    }
    return v;
}


Foam::scalar Foam::immersedDEMChecks::positiveOrDefault
(
    const dictionary& dict,
    const word& key,
    scalar def
)
{
    return dict.found(key, keyType::LITERAL) ? positive(dict, key) : def;
}


Foam::scalar Foam::immersedDEMChecks::inRange
(
    const dictionary& dict,
    const word& key,
    scalar lo,
    scalar hi
)
{
    const scalar v = dict.get<scalar>(key);
    if (!(v >= lo && v <= hi))
    {
        FatalIOErrorInFunction(dict)
            << "Keyword '" << key << "' in " << dict.name() << " is " << v
            << "; it must be in [" << lo << ", " << hi << "]" << nl
            << exit(FatalIOError);
    }
    return v;
}


Foam::scalar Foam::immersedDEMChecks::inRangeOrDefault
(
    const dictionary& dict,
    const word& key,
    scalar lo,
    scalar hi,
    scalar def
)
{
    return dict.found(key, keyType::LITERAL) ? inRange(dict, key, lo, hi) : def;
}


Foam::word Foam::immersedDEMChecks::oneOf
(
    const dictionary& dict,
    const word& key,
    const wordList& valid
)
{
    const word v = dict.get<word>(key);
    if (!valid.found(v))
    {
        FatalIOErrorInFunction(dict)
            << "Unknown " << key << " '" << v << "' in " << dict.name() << nl
            << "Valid " << key << " types are: " << valid << nl
            << exit(FatalIOError);
    }
    return v;
}


Foam::word Foam::immersedDEMChecks::oneOfOrDefault
(
    const dictionary& dict,
    const word& key,
    const wordList& valid,
    const word& def
)
{
    return dict.found(key, keyType::LITERAL) ? oneOf(dict, key, valid) : def;
}


const Foam::dictionary& Foam::immersedDEMChecks::subDictEntry
(
    const dictionary& parent,
    const entry& e,
    const char* what
)
{
    if (!e.isDict())
    {
        FatalIOErrorInFunction(parent)
            << "Entry '" << e.keyword() << "' in " << parent.name()
            << " must be a dictionary of " << what << nl
            << exit(FatalIOError);
    }
    return e.dict();
}


Foam::fileName Foam::immersedDEMChecks::caseFile(const IOobject& io)
{
    return io.time().globalPath()/io.instance()/io.local()/io.name();
}

// File scenes, >>import: assimp's import restricted to the importers of the two formats
// shadesweep reads (see file_internal.h, file_import).
//
// assimp's C API (aiImportFileEx) hands a file to every importer it has (about 50): one
// that claims the file's extension, and where that one declines, any whose signature test
// finds its tokens in the bytes. A malformed .gltf that mentions "geometrynode" reached
// the OpenGEX importer, which read past its buffer (scripts/fuzz.sh found it). shadesweep
// documents, tests and fuzzes glTF 2.0 and OBJ, so only the importers that claim the
// file's own extension stay registered; a file they decline is refused by name.
//
// No C++ exception crosses into C: everything is caught and becomes NULL with a message.
#include "scenes/file/file_import.h"

#include <assimp/BaseImporter.h>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/importerdesc.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <set>
#include <sstream>
#include <string>
#include <strings.h>

namespace {

class Files;

// One file opened through the loader's aiFileIO callbacks (file_io.c).
class Stream : public Assimp::IOStream {
public:
    Stream(Files *files, aiFileIO *io, aiFile *f) : files_(files), io_(io), f_(f) {}
    ~Stream() override;
    size_t Read(void *buf, size_t size, size_t count) override
    {
        return f_->ReadProc(f_, static_cast<char *>(buf), size, count);
    }
    size_t Write(const void *, size_t, size_t) override { return 0; }
    aiReturn Seek(size_t off, aiOrigin origin) override { return f_->SeekProc(f_, off, origin); }
    size_t Tell() const override { return f_->TellProc(f_); }
    size_t FileSize() const override { return f_->FileSizeProc(f_); }
    void Flush() override {}

private:
    Files *files_;
    aiFileIO *io_;
    aiFile *f_;
};

// The loader's aiFileIO as the IOSystem the C++ importer asks for. A stream an importer
// lost on an exception is closed when the importer deletes this (before the scene's
// files are freed), so none outlives the import.
class Files : public Assimp::IOSystem {
public:
    explicit Files(aiFileIO *io) : io_(io) {}
    ~Files() override
    {
        while (!open_.empty())
            delete *open_.begin();   // ~Stream erases it
    }
    void forget(Stream *s) { open_.erase(s); }
    bool Exists(const char *path) const override
    {
        aiFile *f = io_->OpenProc(io_, path, "rb");
        if (f)
            io_->CloseProc(io_, f);
        return f != nullptr;
    }
    char getOsSeparator() const override { return '/'; }
    Assimp::IOStream *Open(const char *path, const char *mode) override
    {
        aiFile *f = io_->OpenProc(io_, path, mode);
        if (!f)
            return nullptr;
        Stream *s = new Stream(this, io_, f);
        open_.insert(s);
        return s;
    }
    void Close(Assimp::IOStream *s) override { delete s; }

private:
    aiFileIO *io_;
    std::set<Stream *> open_;
};

Stream::~Stream()
{
    files_->forget(this);
    io_->CloseProc(io_, f_);
}

// Whether ext (no dot) is one of a space-separated list of extensions.
bool lists(const char *list, const char *ext)
{
    std::istringstream words(list ? list : "");
    std::string w;
    while (words >> w)
        if (strcasecmp(w.c_str(), ext) == 0)
            return true;
    return false;
}

// The formats shadesweep documents, tests and fuzzes.
bool read_here(const char *ext)
{
    return strcasecmp(ext, "gltf") == 0 || strcasecmp(ext, "glb") == 0 ||
           strcasecmp(ext, "obj") == 0;
}

void set_err(char *err, size_t errlen, const std::string &msg)
{
    if (err && errlen)
        std::snprintf(err, errlen, "%s", msg.c_str());
}

} // namespace

const struct aiScene *file_import(const char *path, unsigned flags, aiFileIO *io,
                                  int drop_primitives, char *err, size_t errlen)
{
    try {
        const char *dot = std::strrchr(path, '.');
        const char *slash = std::strrchr(path, '/');
        const char *ext = dot && (!slash || dot > slash) ? dot + 1 : "";
        if (!read_here(ext)) {
            set_err(err, errlen, (ext[0] ? std::string("the extension '.") + ext + "' is not"
                                         : std::string("the file has no extension, not")) +
                                     " one shadesweep reads: .gltf, .glb (glTF 2.0) or .obj "
                                     "(Wavefront OBJ)");
            return nullptr;
        }
        Assimp::Importer imp;
        for (size_t i = imp.GetImporterCount(); i-- > 0;) {
            const aiImporterDesc *d = imp.GetImporterInfo(i);
            if (d && lists(d->mFileExtensions, ext))
                continue;
            Assimp::BaseImporter *b = imp.GetImporter(i);
            // UnregisterLoader only drops it from the list: the object is ours to delete
            if (b && imp.UnregisterLoader(b) == aiReturn_SUCCESS)
                delete b;
        }
        imp.SetIOHandler(new Files(io));   // the importer owns and deletes it
        if (drop_primitives)
            imp.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, drop_primitives);
        if (!imp.ReadFile(path, flags)) {
            const char *why = imp.GetErrorString();
            if (why && std::strncmp(why, "No suitable reader", 18) == 0)
                set_err(err, errlen, std::string("not a ") +
                                         (strcasecmp(ext, "obj") == 0 ? "OBJ" : "glTF") +
                                         " file that assimp reads (no other format is tried "
                                         "for a ." + ext + " file)");
            else
                set_err(err, errlen, why && why[0] ? why : "unknown error");
            return nullptr;
        }
        // freed by aiReleaseImport: an orphaned scene carries no importer
        return imp.GetOrphanedScene();
    } catch (const std::exception &e) {
        set_err(err, errlen, e.what());
    } catch (...) {
        set_err(err, errlen, "unknown error");
    }
    return nullptr;
}

// VTK unstructured grids to a biref_pe_mesh through VTK's readers (see fea_vtk.h). C++ because
// VTK is; everything the rest of the command sees is the C interface.
#include "fea_vtk.h"

#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>
#include <strings.h>
#include <vector>

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkDataSet.h>
#include <vtkErrorCode.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLGenericDataObjectReader.h>

namespace {

biref_status fail(char *msg, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
biref_status fail(char *msg, size_t len, const char *fmt, ...)
{
    if (msg && len) {
        va_list ap;
        va_start(ap, fmt);
        std::vsnprintf(msg, len, fmt, ap);
        va_end(ap);
    }
    return BIREF_ERR_INVALID;
}

// The point-data array named name (case-insensitive), or null.
vtkDataArray *array_named(vtkFieldData *fd, const char *name)
{
    for (int i = 0; i < fd->GetNumberOfArrays(); i++) {
        vtkDataArray *a = fd->GetArray(i);
        if (a && a->GetName() && !strcasecmp(a->GetName(), name)) return a;
    }
    return nullptr;
}

std::string array_list(vtkFieldData *fd)
{
    std::string s;
    for (int i = 0; i < fd->GetNumberOfArrays() && s.size() < 200; i++) {
        vtkDataArray *a = fd->GetArray(i);
        if (!a || !a->GetName()) continue;
        if (!s.empty()) s += ", ";
        s += a->GetName();
        s += " (" + std::to_string(a->GetNumberOfComponents()) + ")";
    }
    return s.empty() ? "none" : s;
}

// Component indices of xx, yy, xy in a tensor array, or false.
bool tensor_layout(int nc, int idx[3])
{
    if (nc == 3) idx[0] = 0, idx[1] = 1, idx[2] = 2;      // plane: xx, yy, xy
    else if (nc == 6) idx[0] = 0, idx[1] = 1, idx[2] = 3; // VTK symmetric: xx, yy, zz, xy, yz, xz
    else if (nc == 9) idx[0] = 0, idx[1] = 4, idx[2] = 1; // full 3 x 3, row-major
    else return false;
    return true;
}

// The nodal stresses (Pa) from the requested or the usual arrays.
biref_status stresses(vtkDataSet *ds, const pe_vtk_request *req, std::vector<double> &s, char *used, char *msg,
                      size_t len)
{
    vtkPointData *pd = ds->GetPointData();
    const vtkIdType n = ds->GetNumberOfPoints();
    vtkDataArray *a[3] = {nullptr, nullptr, nullptr};
    int idx[3] = {0, 0, 0};
    const char *tensors[] = {"stress", "S", "sigma", "stresses"};
    const char *scalars[][3] = {{"stress_xx", "stress_yy", "stress_xy"}, {"sxx", "syy", "sxy"}, {"S11", "S22", "S12"},
                                {"sxx", "syy", "txy"}};
    if (req->tensor) {
        a[0] = array_named(pd, req->tensor);
        if (!a[0])
            return fail(msg, len, "no point-data array '%s' (point data: %s)", req->tensor, array_list(pd).c_str());
    } else if (req->comp[0]) {
        for (int c = 0; c < 3; c++)
            if (!(a[c] = array_named(pd, req->comp[c])))
                return fail(msg, len, "no point-data array '%s' (point data: %s)", req->comp[c], array_list(pd).c_str());
    } else {
        for (const char *t : tensors)
            if (!a[0] && (a[0] = array_named(pd, t)) && !tensor_layout(a[0]->GetNumberOfComponents(), idx)) a[0] = nullptr;
        for (auto &sc : scalars)
            if (!a[0] && array_named(pd, sc[0]) && array_named(pd, sc[1]) && array_named(pd, sc[2]))
                for (int c = 0; c < 3; c++) a[c] = array_named(pd, sc[c]);
        if (!a[0]) {
            vtkCellData *cd = ds->GetCellData();
            for (const char *t : tensors)
                if (array_named(cd, t))
                    return fail(msg, len, "the stress '%s' is cell data (one value per element); export nodal stresses "
                                "(ParaView: Cell Data to Point Data)", t);
            return fail(msg, len, "no stress array found (point data: %s); name it with --fea-stress NAME or --columns "
                        "sxx=...,syy=...,txy=...", array_list(pd).c_str());
        }
    }
    if (!a[1]) {
        if (!tensor_layout(a[0]->GetNumberOfComponents(), idx))
            return fail(msg, len, "array '%s' has %d components; a stress tensor has 3 (xx, yy, xy), 6 (xx, yy, zz, xy, "
                        "yz, xz) or 9", a[0]->GetName(), a[0]->GetNumberOfComponents());
        std::snprintf(used, 96, "%.60s (tensor, %d components)", a[0]->GetName(), a[0]->GetNumberOfComponents());
    } else {
        for (int c = 0; c < 3; c++)
            if (a[c]->GetNumberOfComponents() != 1)
                return fail(msg, len, "array '%s' has %d components, expected 1", a[c]->GetName(),
                            a[c]->GetNumberOfComponents());
        std::snprintf(used, 96, "%.28s, %.28s, %.28s", a[0]->GetName(), a[1]->GetName(), a[2]->GetName());
    }
    s.resize(3 * (size_t)n);
    for (vtkIdType i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            double v = a[1] ? a[c]->GetComponent(i, 0) : a[0]->GetComponent(i, idx[c]);
            s[3 * (size_t)i + c] = v * req->stress_pa;
        }
    return BIREF_OK;
}

// The plane cells; vertices and edges (gmsh's boundary lines) are skipped, solids refused.
biref_status cells(vtkDataSet *ds, std::vector<int> &type, std::vector<size_t> &conn, char *msg, size_t len)
{
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < ds->GetNumberOfCells(); c++) {
        int t;
        switch (ds->GetCellType(c)) {
        case VTK_TRIANGLE: t = BIREF_PE_TRI3; break;
        case VTK_QUADRATIC_TRIANGLE: t = BIREF_PE_TRI6; break;
        case VTK_QUAD: t = BIREF_PE_QUAD4; break;
        case VTK_QUADRATIC_QUAD: t = BIREF_PE_QUAD8; break;
        case VTK_BIQUADRATIC_QUAD: t = BIREF_PE_QUAD9; break;
        case VTK_VERTEX: case VTK_POLY_VERTEX: case VTK_LINE: case VTK_POLY_LINE: case VTK_QUADRATIC_EDGE: continue;
        case VTK_POLYGON: case VTK_TRIANGLE_STRIP: case VTK_PIXEL:
            return fail(msg, len, "cell %lld is a polygon, strip or pixel: triangulate the mesh (ParaView: Triangulate)",
                        (long long)c);
        default:
            return fail(msg, len, "cell %lld is a 3-D cell (VTK type %d): biref pictures plane stress; export a "
                        "plane-stress model, or a section in the x-y plane (ParaView: Slice, then Triangulate)",
                        (long long)c, ds->GetCellType(c));
        }
        ds->GetCellPoints(c, ids);
        if (ids->GetNumberOfIds() != biref_pe_element_nodes((biref_pe_element_type)t))
            return fail(msg, len, "cell %lld has %lld points for its type", (long long)c, (long long)ids->GetNumberOfIds());
        type.push_back(t);
        for (vtkIdType k = 0; k < ids->GetNumberOfIds(); k++) conn.push_back((size_t)ids->GetId(k));
    }
    if (type.empty()) return fail(msg, len, "no plane cells (triangles or quadrilaterals, linear or quadratic)");
    return BIREF_OK;
}

vtkSmartPointer<vtkDataObject> read(const char *path, int legacy, char *msg, size_t len, biref_status *st)
{
    vtkSmartPointer<vtkDataObject> out;
    if (legacy) {
        vtkNew<vtkGenericDataObjectReader> r;
        r->SetFileName(path);
        r->Update();
        if (r->GetErrorCode() != vtkErrorCode::NoError || !r->GetOutput()) {
            *st = fail(msg, len, "cannot read as a legacy VTK file (%s)",
                       vtkErrorCode::GetStringFromErrorCode(r->GetErrorCode()));
            return nullptr;
        }
        out = r->GetOutput();
    } else {
        vtkNew<vtkXMLGenericDataObjectReader> r;
        r->SetFileName(path);
        r->Update();
        if (r->GetErrorCode() != vtkErrorCode::NoError || !r->GetOutput()) {
            *st = fail(msg, len, "cannot read as a VTK XML file (%s)", vtkErrorCode::GetStringFromErrorCode(r->GetErrorCode()));
            return nullptr;
        }
        out = r->GetOutput();
    }
    return out;
}

} // namespace

extern "C" int pe_vtk_available(void)
{
    return 1;
}

extern "C" biref_status pe_vtk_load(const char *path, int legacy, const pe_vtk_request *req, biref_pe_mesh **out,
                                    char *used, char *msg, size_t msg_len)
{
    *out = nullptr;
    used[0] = '\0';
    std::FILE *f = std::fopen(path, "rb");
    if (!f) return fail(msg, msg_len, "cannot read: %s", std::strerror(errno)), BIREF_ERR_IO;
    std::fclose(f);
    vtkObject::GlobalWarningDisplayOff(); // the reader's complaints become our one line
    biref_status st = BIREF_OK;
    vtkSmartPointer<vtkDataObject> obj = read(path, legacy, msg, msg_len, &st);
    if (!obj) return st;
    vtkDataSet *ds = vtkDataSet::SafeDownCast(obj);
    if (!ds || ds->GetNumberOfPoints() == 0 || ds->GetNumberOfCells() == 0)
        return fail(msg, msg_len, "no points or cells read (not an unstructured grid or polydata, or a damaged file)");
    const vtkIdType n = ds->GetNumberOfPoints();
    std::vector<double> xy(2 * (size_t)n), s;
    double zlo = INFINITY, zhi = -INFINITY, ext = 0;
    for (vtkIdType i = 0; i < n; i++) {
        double p[3];
        ds->GetPoint(i, p);
        xy[2 * (size_t)i] = p[0] * req->length_m;
        xy[2 * (size_t)i + 1] = p[1] * req->length_m;
        zlo = std::fmin(zlo, p[2]), zhi = std::fmax(zhi, p[2]);
        ext = std::fmax(ext, std::fmax(std::fabs(p[0]), std::fabs(p[1])));
    }
    std::vector<int> type;
    std::vector<size_t> conn;
    if ((st = cells(ds, type, conn, msg, msg_len)) != BIREF_OK) return st;
    if (zhi - zlo > 1e-9 * ext)
        return fail(msg, msg_len, "the points are not in one plane z = const (z %g..%g): a shell or a 3-D part; export a "
                    "plane-stress model, or a section in the x-y plane", zlo, zhi);
    if ((st = stresses(ds, req, s, used, msg, msg_len)) != BIREF_OK) return st;
    biref_pe_elements el = {(size_t)n, xy.data(), s.data(), type.size(), type.data(), conn.data()};
    return biref_pe_mesh_from_elements(&el, out, msg, msg_len);
}
